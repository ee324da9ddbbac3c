"""BibTeX references of the implemented methods: :func:`citation`.

A small database of the papers the methods implement (taken from the
``References`` sections of their docstrings and the reference lists of the
papers they implement) and a map from every method name to its entries. DOIs are given only
where they were confirmed (printed in one of those papers); the others are left out
rather than guessed.

Examples
--------
>>> import wheelrail as wr
>>> print(wr.citation("fastsim"))            # doctest: +ELLIPSIS
@article{Kalker1982,
...
>>> bib = wr.citation(wr.solve(wr.hertz(1e4, 1.0, 2.0, wr.STEEL), (1e-3, 0, 0), 0.3))
"""

from __future__ import annotations

from .errors import InputError

__all__ = ["BIBLIOGRAPHY", "METHOD_REFERENCES", "citation", "citation_keys", "bibtex"]

#: key -> (entry type, fields). Field values are plain text (BibTeX braces added on output).
BIBLIOGRAPHY: dict[str, tuple[str, dict[str, str]]] = {
    "Hertz1882": ("article", {
        "author": "Hertz, Heinrich",
        "title": "Ueber die Ber{\\\"u}hrung fester elastischer K{\\\"o}rper",
        "journal": "Journal f{\\\"u}r die reine und angewandte Mathematik",
        "volume": "92", "pages": "156--171", "year": "1882"}),
    "Johnson1985": ("book", {
        "author": "Johnson, Kenneth L.",
        "title": "Contact Mechanics",
        "publisher": "Cambridge University Press", "address": "Cambridge", "year": "1985"}),
    "Carter1926": ("article", {
        "author": "Carter, F. W.",
        "title": "On the action of a locomotive driving wheel",
        "journal": "Proceedings of the Royal Society of London, Series A",
        "volume": "112", "pages": "151--157", "year": "1926"}),
    "HainesOllerton1963": ("article", {
        "author": "Haines, D. J. and Ollerton, E.",
        "title": "Contact stress distributions on elliptical contact surfaces subjected to "
                 "radial and tangential forces",
        "journal": "Proceedings of the Institution of Mechanical Engineers",
        "volume": "177", "pages": "95--114", "year": "1963"}),
    "Cattaneo1938": ("article", {
        "author": "Cattaneo, C.",
        "title": "Sul contatto di due corpi elastici: distribuzione locale degli sforzi",
        "journal": "Rendiconti dell'Accademia Nazionale dei Lincei",
        "volume": "27", "pages": "342--348, 434--436, 474--478", "year": "1938"}),
    "Mindlin1949": ("article", {
        "author": "Mindlin, R. D.",
        "title": "Compliance of elastic bodies in contact",
        "journal": "Journal of Applied Mechanics",
        "volume": "16", "pages": "259--268", "year": "1949"}),
    "Kalker1967": ("phdthesis", {
        "author": "Kalker, Joost J.",
        "title": "On the rolling contact of two elastic bodies in the presence of dry friction",
        "school": "Delft University of Technology", "year": "1967"}),
    "Kalker1982": ("article", {
        "author": "Kalker, Joost J.",
        "title": "A fast algorithm for the simplified theory of rolling contact",
        "journal": "Vehicle System Dynamics",
        "volume": "11", "number": "1", "pages": "1--13", "year": "1982"}),
    "Kalker1990": ("book", {
        "author": "Kalker, Joost J.",
        "title": "Three-Dimensional Elastic Bodies in Rolling Contact",
        "series": "Solid Mechanics and its Applications", "volume": "2",
        "publisher": "Kluwer Academic Publishers", "address": "Dordrecht", "year": "1990"}),
    "Kalker1996": ("inproceedings", {
        "author": "Kalker, Joost J.",
        "title": "Book of tables for the Hertzian creep-force law",
        "booktitle": "Proceedings of the 2nd Mini Conference on Contact Mechanics and Wear "
                     "of Wheel/Rail Systems",
        "address": "Budapest", "pages": "11--20", "year": "1996"}),
    "Panagiotopoulos1975": ("article", {
        "author": "Panagiotopoulos, P. D.",
        "title": "A nonlinear programming approach to the unilateral contact- and "
                 "friction-boundary value problem in the theory of elasticity",
        "journal": "Ingenieur-Archiv",
        "volume": "44", "pages": "421--432", "year": "1975"}),
    "Zhao2015": ("article", {
        "author": "Zhao, Jing and Vollebregt, Edwin A. H. and Oosterlee, Cornelis W.",
        "title": "A fast nonlinear conjugate gradient based method for 3D frictional "
                 "contact problems",
        "journal": "Journal of Computational Physics",
        "volume": "288", "pages": "86--100", "year": "2015"}),
    "PolonskyKeer1999": ("article", {
        "author": "Polonsky, I. A. and Keer, L. M.",
        "title": "A numerical method for solving rough contact problems based on the "
                 "multi-level multi-summation and conjugate gradient techniques",
        "journal": "Wear", "volume": "231", "pages": "206--219", "year": "1999"}),
    "ShenHedrickElkins1983": ("inproceedings", {
        "author": "Shen, Z. Y. and Hedrick, J. K. and Elkins, J. A.",
        "title": "A comparison of alternative creep force models for rail vehicle dynamic "
                 "analysis",
        "booktitle": "The Dynamics of Vehicles on Roads and Tracks, Proceedings of the 8th "
                     "IAVSD Symposium",
        "address": "Cambridge, MA", "pages": "591--605", "year": "1983"}),
    "JohnsonVermeulen1964": ("article", {
        "author": "Johnson, K. L. and Vermeulen, P. J.",
        "title": "Contact of nonspherical elastic bodies transmitting tangential forces",
        "journal": "Journal of Applied Mechanics",
        "volume": "31", "pages": "338--340", "year": "1964"}),
    "Polach1999": ("article", {
        "author": "Polach, Oldrich",
        "title": "A fast wheel-rail forces calculation computer code",
        "journal": "Vehicle System Dynamics",
        "volume": "33", "number": "Supplement", "pages": "728--739", "year": "1999"}),
    "Polach2005": ("article", {
        "author": "Polach, Oldrich",
        "title": "Creep forces in simulations of traction vehicles running on adhesion limit",
        "journal": "Wear", "volume": "258", "pages": "992--1000", "year": "2005"}),
    "PiotrowskiChollet2005": ("article", {
        "author": "Piotrowski, J. and Chollet, H.",
        "title": "Wheel-rail contact models for vehicle system dynamics including multi-point "
                 "contact",
        "journal": "Vehicle System Dynamics",
        "volume": "43", "number": "6-7", "pages": "455--483", "year": "2005",
        "doi": "10.1080/00423110500141144"}),
    "PiotrowskiKik2008": ("article", {
        "author": "Piotrowski, J. and Kik, W.",
        "title": "A simplified model of wheel/rail contact mechanics for non-Hertzian "
                 "problems and its application in rail vehicle dynamic simulations",
        "journal": "Vehicle System Dynamics",
        "volume": "46", "pages": "27--48", "year": "2008",
        "doi": "10.1080/00423110701586444"}),
    "KikPiotrowski1996": ("inproceedings", {
        "author": "Kik, W. and Piotrowski, J.",
        "title": "A fast, approximate method to calculate normal load at contact between "
                 "wheel and rail and creep forces during rolling",
        "booktitle": "Proceedings of the 2nd Mini Conference on Contact Mechanics and Wear "
                     "of Wheel/Rail Systems",
        "address": "Budapest", "year": "1996"}),
    "Linder1997": ("phdthesis", {
        "author": "Linder, C.",
        "title": "Verschlei{\\ss} von Eisenbahnr{\\\"a}dern mit Unrundheiten",
        "school": "ETH Z{\\\"u}rich", "note": "Dissertation Nr. 12342", "year": "1997"}),
    "AyasseChollet2005": ("article", {
        "author": "Ayasse, J. B. and Chollet, H.",
        "title": "Determination of the wheel rail contact patch in semi-Hertzian conditions",
        "journal": "Vehicle System Dynamics",
        "volume": "43", "number": "3", "pages": "161--172", "year": "2005",
        "doi": "10.1080/00423110412331327193"}),
    "AyasseCholletMaupu2000": ("techreport", {
        "author": "Ayasse, J. B. and Chollet, H. and Maupu, J. L.",
        "title": "Param{\\`e}tres caract{\\'e}ristiques du contact roue-rail",
        "institution": "INRETS", "number": "225", "year": "2000"}),
    "PascalSauvage1993": ("article", {
        "author": "Pascal, J. P. and Sauvage, G.",
        "title": "The available methods to calculate the wheel/rail forces in non Hertzian "
                 "contact patches and rail damaging",
        "journal": "Vehicle System Dynamics",
        "volume": "22", "pages": "263--275", "year": "1993"}),
    "Sichani2016": ("article", {
        "author": "Sichani, Matin Sh. and Enblom, Roger and Berg, Mats",
        "title": "An alternative to FASTSIM for tangential solution of the wheel-rail contact",
        "journal": "Vehicle System Dynamics",
        "volume": "54", "number": "6", "pages": "748--764", "year": "2016",
        "doi": "10.1080/00423114.2016.1156135"}),
    "VollebregtVoltr2023": ("article", {
        "author": "Vollebregt, Edwin A. H. and Voltr, Petr",
        "title": "Improved accuracy for FASTSIM using one or three flexibility values",
        "journal": "Vehicle System Dynamics", "year": "2023",
        "note": "FASTSIM with three flexibilities saturating in the slip direction; cited "
                "here, title and venue not confirmed against the paper"}),
    "Vollebregt2022": ("article", {
        "author": "Vollebregt, Edwin A. H.",
        "title": "Detailed wheel/rail geometry processing using the planar contact approach",
        "journal": "Vehicle System Dynamics",
        "volume": "60", "pages": "1253--1291", "year": "2022"}),
    "VollebregtCONTACT": ("manual", {
        "author": "Vollebregt, Edwin A. H.",
        "title": "User guide for CONTACT, rolling and sliding contact with friction",
        "organization": "Vtech CMCC", "year": "2025",
        "note": "Program CONTACT, open-source revision 2707 (reference output of the "
                "Manchester benchmark A-2.2)"}),
    "Baeza": ("misc", {
        "author": "Baeza, L. and Fuenmayor, F. J. and Carballeira, J. and Roda, A.",
        "title": "Influence of the wheel-rail contact instationary process on contact "
                 "parameters",
        "howpublished": "Universidad Polit{\\'e}cnica de Valencia",
        "note": "Transient rolling, eqs. (2.5)--(2.22); year and venue not confirmed"}),
    "Toumi2016": ("article", {
        "author": "Toumi, Moncef and Chollet, Hugues and Yin, Honor{\\'e}",
        "title": "Finite element analysis of the frictional wheel-rail rolling contact using "
                 "explicit and implicit methods",
        "journal": "Wear", "volume": "366-367", "pages": "157--166", "year": "2016",
        "doi": "10.1016/j.wear.2016.06.008"}),
    "Bosso2013": ("book", {
        "author": "Bosso, Nicola and Spiryagin, Maksym and Gugliotta, Antonio and "
                  "Som{\\`a}, Aurelio",
        "title": "Mechatronic Modeling of Real-Time Wheel-Rail Contact",
        "publisher": "Springer", "address": "Berlin, Heidelberg", "year": "2013",
        "note": "Chapter 2, Review of wheel-rail contact models"}),
    # wear and rolling-contact fatigue (wheelrail.wear)
    "Archard1953": ("article", {
        "author": "Archard, J. F.",
        "title": "Contact and rubbing of flat surfaces",
        "journal": "Journal of Applied Physics",
        "volume": "24", "pages": "981--988", "year": "1953"}),
    "Jendel2002": ("article", {
        "author": "Jendel, Tomas",
        "title": "Prediction of wheel profile wear---comparisons with field measurements",
        "journal": "Wear", "volume": "253", "pages": "89--99", "year": "2002"}),
    "EnblomBerg2005": ("article", {
        "author": "Enblom, Roger and Berg, Mats",
        "title": "Simulation of railway wheel profile development due to wear---influence of "
                 "disc braking and contact environment",
        "journal": "Wear", "volume": "258", "pages": "1055--1063", "year": "2005"}),
    "LewisDwyerJoyce2004": ("article", {
        "author": "Lewis, R. and Dwyer-Joyce, R. S.",
        "title": "Wear mechanisms and transitions in railway wheel steels",
        "journal": "Proceedings of the Institution of Mechanical Engineers, Part J: Journal "
                   "of Engineering Tribology",
        "volume": "218", "pages": "467--478", "year": "2004"}),
    "Braghin2006": ("article", {
        "author": "Braghin, F. and Lewis, R. and Dwyer-Joyce, R. S. and Bruni, S.",
        "title": "A mathematical model to predict railway wheel profile evolution due to wear",
        "journal": "Wear", "volume": "261", "pages": "1253--1264", "year": "2006"}),
    "Lewis2010": ("article", {
        "author": "Lewis, R. and Dwyer-Joyce, R. S. and Olofsson, U. and Pombo, J. and "
                  "Ambr{\\'o}sio, J. and Pereira, M. and Ariaudo, C. and Kuka, N.",
        "title": "Mapping railway wheel material wear mechanisms and transitions",
        "journal": "Proceedings of the Institution of Mechanical Engineers, Part F: Journal "
                   "of Rail and Rapid Transit",
        "volume": "224", "pages": "125--137", "year": "2010"}),
    "PearceSherratt1991": ("article", {
        "author": "Pearce, T. G. and Sherratt, N. D.",
        "title": "Prediction of wheel profile wear",
        "journal": "Wear", "volume": "144", "pages": "343--351", "year": "1991"}),
    "Ekberg2002": ("article", {
        "author": "Ekberg, A. and Kabo, E. and Andersson, H.",
        "title": "An engineering model for prediction of rolling contact fatigue of railway "
                 "wheels",
        "journal": "Fatigue \\& Fracture of Engineering Materials \\& Structures",
        "volume": "25", "pages": "899--909", "year": "2002"}),
    "Burstow2004": ("techreport", {
        "author": "Burstow, M.",
        "title": "Whole life rail model application and development for RSSB---continued "
                 "development of an RCF damage parameter",
        "institution": "Rail Safety and Standards Board", "number": "AEATR-ES-2004-880",
        "year": "2004"}),
    "Johnson1989": ("article", {
        "author": "Johnson, K. L.",
        "title": "The strength of surfaces in rolling contact",
        "journal": "Proceedings of the Institution of Mechanical Engineers, Part C",
        "volume": "203", "pages": "151--163", "year": "1989"}),
}

#: method name -> keys of :data:`BIBLIOGRAPHY` (the papers it implements, first the main one).
METHOD_REFERENCES: dict[str, tuple[str, ...]] = {
    # normal methods (wr.normal_methods())
    "hertz": ("Hertz1882", "Johnson1985"),
    "bem": ("Kalker1990", "PolonskyKeer1999"),
    "kik-piotrowski": ("PiotrowskiKik2008", "KikPiotrowski1996", "PiotrowskiChollet2005"),
    "linder": ("Linder1997", "PiotrowskiChollet2005"),
    "stripes": ("AyasseChollet2005", "PiotrowskiChollet2005"),
    "multi-hertz": ("PascalSauvage1993", "AyasseCholletMaupu2000", "PiotrowskiChollet2005"),
    # tangential methods (wr.tangential_methods())
    "carter": ("Carter1926", "HainesOllerton1963", "Johnson1985"),
    "linear": ("Kalker1967", "Kalker1990"),
    "fastsim": ("Kalker1982", "Kalker1990", "PiotrowskiChollet2005", "VollebregtVoltr2023"),
    "shen-hedrick-elkins": ("ShenHedrickElkins1983", "JohnsonVermeulen1964", "Kalker1990"),
    "polach": ("Polach1999", "Polach2005", "Kalker1990"),
    "exact": ("Kalker1990", "Panagiotopoulos1975", "Zhao2015"),
    "table": ("Kalker1996", "Kalker1990"),
    "fastrip": ("Sichani2016", "Kalker1990"),
    # other solvers of the package
    "transient": ("Baeza", "Kalker1990"),
    "fe": ("Toumi2016",),
    "geometry": ("Bosso2013", "PiotrowskiChollet2005"),
    "halfspace": ("Johnson1985", "Kalker1990"),
    "cattaneo": ("Cattaneo1938", "Mindlin1949", "Johnson1985"),
    "manchester": ("Vollebregt2022", "VollebregtCONTACT"),
    # wear laws (wr.wear.wear_laws()), RCF indices and the profile-evolution loop
    "archard": ("Archard1953", "Jendel2002"),
    "kth": ("Jendel2002", "EnblomBerg2005"),
    "usfd": ("LewisDwyerJoyce2004", "Braghin2006", "Lewis2010"),
    "energy": ("PearceSherratt1991", "Braghin2006"),
    "rcf": ("Ekberg2002", "Burstow2004", "Johnson1989"),
    "wear": ("Jendel2002", "Braghin2006", "EnblomBerg2005"),
}

_ALIASES = {
    "kalker-linear": "linear", "she": "shen-hedrick-elkins",
    "shen_hedrick_elkins": "shen-hedrick-elkins", "kalker": "exact",
    "kik_piotrowski": "kik-piotrowski", "multi_hertz": "multi-hertz",
    "transient_rolling": "transient", "transient-rolling": "transient",
    "contact": "manchester", "kth-map": "kth", "kthmap": "kth", "tgamma": "usfd",
    "burstow": "rcf", "fatigue": "rcf",
}


def _names_of(item) -> list[str]:
    """Method names used by ``item``: a name, a method object or a result object."""
    if isinstance(item, str):
        key = item.lower().split("/")[0]      # "multi-hertz/sauvage" -> "multi-hertz"
        key = _ALIASES.get(key, key)
        if key not in METHOD_REFERENCES:
            raise InputError(f"no citation for method {item!r}; known methods: "
                             + ", ".join(METHOD_REFERENCES))
        return [key]
    if isinstance(item, (list, tuple, set, frozenset)):
        return [n for x in item for n in _names_of(x)]
    names: list[str] = []
    # ContactResult / WheelRailResult: normal and tangential method names
    for attr in ("normal", "tangential"):
        value = getattr(item, attr, None)
        if isinstance(value, str):
            names.extend(_names_of(value))
    # CreepForcesResult, ContactPatch, method objects: a ``method`` or ``name`` string
    if not names:
        for attr in ("method", "name"):
            value = getattr(item, attr, None)
            if isinstance(value, str) and value:
                names.extend(_names_of(value))
                break
    if not names:
        module = type(item).__module__
        if module.startswith("wheelrail.transient"):
            names.append("transient")
        elif module.startswith("wheelrail.fe"):
            names.append("fe")
        elif module.startswith("wheelrail.geometry"):
            names.append("geometry")
        elif module.startswith("wheelrail.wear.fatigue"):
            names.append("rcf")
        elif module.startswith("wheelrail.wear"):
            names.append("wear")
    if not names:
        raise InputError(f"cannot tell which methods made {type(item).__name__!r}; pass method "
                         "names (e.g. 'fastsim', 'kik-piotrowski') or a wheelrail result")
    return names


def citation_keys(*items) -> list[str]:
    """BibTeX keys of the methods used by ``items`` (all methods if none), without duplicates."""
    names = list(METHOD_REFERENCES) if not items else [n for it in items for n in _names_of(it)]
    keys: list[str] = []
    for n in names:
        keys.extend(k for k in METHOD_REFERENCES[n] if k not in keys)
    return keys


def bibtex(key: str) -> str:
    """One BibTeX entry of :data:`BIBLIOGRAPHY` as text."""
    if key not in BIBLIOGRAPHY:
        raise InputError(f"unknown citation key {key!r}")
    kind, fields = BIBLIOGRAPHY[key]
    width = max(len(f) for f in fields)
    body = ",\n".join(f"  {f.ljust(width)} = {{{v}}}" for f, v in fields.items())
    return f"@{kind}{{{key},\n{body}\n}}"


def citation(*items) -> str:
    """BibTeX of every method used in a result (or of the named methods).

    Parameters
    ----------
    *items : str, result or method object
        Method names (``"fastsim"``, ``"kik-piotrowski"``, ``"exact"``,
        ``"transient"``, ``"fe"``, ``"geometry"``, ...; aliases such as
        ``"she"`` accepted; the wear laws ``"archard"``, ``"kth"``, ``"usfd"``,
        ``"energy"``, ``"rcf"`` and the wear loop ``"wear"``), results (:class:`~wheelrail.results.ContactResult`,
        :class:`~wheelrail.contact.wheelrail.WheelRailResult`,
        :class:`~wheelrail.results.CreepForcesResult`, transient and FE results) or
        method objects. None: the references of every method of the package.

    Returns
    -------
    str
        BibTeX entries separated by blank lines, each reference once, in the
        order the methods are given (main reference of each method first).

    Raises
    ------
    InputError
        An unknown method name or an object whose methods cannot be told.

    References
    ----------
    The entries are those of the methods' docstrings (``References`` sections
    and ``references`` attributes) and of the reference lists of the papers they
    implement.
    """
    return "\n\n".join(bibtex(k) for k in citation_keys(*items)) + "\n"
