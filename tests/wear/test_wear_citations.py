"""wr.citation() of the wear laws, the RCF indices and the wear loop: the papers the
docstrings cite (References sections of wheelrail.wear), each law its own source first."""

import pytest

import wheelrail as wr
from wheelrail.citations import BIBLIOGRAPHY


@pytest.mark.parametrize("item, first, also", [
    ("archard", "Archard1953", "Jendel2002"),
    ("kth", "Jendel2002", "EnblomBerg2005"),
    ("usfd", "LewisDwyerJoyce2004", "Braghin2006"),
    ("tgamma", "LewisDwyerJoyce2004", "Braghin2006"),
    ("energy", "PearceSherratt1991", "Braghin2006"),
    ("rcf", "Ekberg2002", "Burstow2004"),
    ("wear", "Jendel2002", "Braghin2006"),
])
def test_wear_names_cite_their_sources(item, first, also):
    bib = wr.citation(item)
    assert bib.lstrip().split("\n")[0].endswith(f"{{{first},")
    assert f"{{{also}," in bib


def test_configured_laws_and_results_are_cited():
    assert "{Archard1953," in wr.citation(wr.wear.Archard(k=2e-4))
    assert "{Jendel2002," in wr.citation(wr.wear.KTHMap())
    assert "{LewisDwyerJoyce2004," in wr.citation(wr.wear.USFD())
    assert "{PearceSherratt1991," in wr.citation(wr.wear.Energy())
    assert "{Burstow2004," in wr.citation(wr.wear.Burstow())
    # every wear law registered has an entry, with the year of its docstring reference
    for name in wr.wear.wear_laws():
        assert wr.citation(name).startswith("@")
    assert BIBLIOGRAPHY["Braghin2006"][1]["volume"] == "261"
    assert BIBLIOGRAPHY["Jendel2002"][1]["pages"] == "89--99"
