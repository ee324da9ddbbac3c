"""wr.citation(): BibTeX for every method, well formed (unique keys, required fields)."""

import re

import pytest

import wheelrail as wr
from wheelrail.citations import BIBLIOGRAPHY, METHOD_REFERENCES, citation_keys

# required fields per entry type (BibTeX's standard styles)
REQUIRED = {"article": {"author", "title", "journal", "year"},
            "book": {"author", "title", "publisher", "year"},
            "inproceedings": {"author", "title", "booktitle", "year"},
            "phdthesis": {"author", "title", "school", "year"},
            "techreport": {"author", "title", "institution", "year"},
            "manual": {"title"}, "misc": set()}


def _parse(text):
    """A small BibTeX reader: entries -> (type, key, {field: value}) with balanced braces."""
    entries = []
    for m in re.finditer(r"@(\w+)\{([^,\s]+),", text):
        i, depth = m.end(), 1
        while depth:
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        body = text[m.end():i - 1]
        fields = dict(re.findall(r"^\s*(\w+)\s*=\s*\{(.*)\},?\s*$", body, flags=re.M))
        entries.append((m.group(1), m.group(2), fields))
    return entries


def test_every_registered_method_has_a_citation():
    for name in [*wr.normal_methods(), *wr.tangential_methods(), "transient", "fe", "geometry"]:
        bib = wr.citation(name)
        assert bib.startswith("@") and len(_parse(bib)) >= 1, name


def test_whole_database_parses_keys_unique_required_fields():
    text = wr.citation()
    entries = _parse(text)
    keys = [k for _, k, _ in entries]
    assert len(keys) == len(set(keys))
    assert set(keys) == set(citation_keys())
    for kind, key, fields in entries:
        assert REQUIRED[kind] <= set(fields), (key, REQUIRED[kind] - set(fields))
        if "year" in fields:
            assert re.fullmatch(r"1[89]\d\d|20\d\d", fields["year"]), key
    for keys_ in METHOD_REFERENCES.values():
        assert all(k in BIBLIOGRAPHY for k in keys_)


def test_citation_of_results_and_names():
    c = wr.hertz(1e4, 1.0, 2.0, wr.STEEL)
    res = wr.solve(c, creepage=(1e-3, 0, 0), mu=0.3, normal="hertz", tangential="fastsim")
    bib = wr.citation(res)
    assert "@article{Hertz1882," in bib and "@article{Kalker1982," in bib
    cf = wr.creep_forces(c, (1e-3, 0, 0), 0.3, method="polach")
    assert "Polach1999" in wr.citation(cf)
    # several items, each reference once, aliases and variants accepted
    bib = wr.citation("fastsim", "she", "multi-hertz/sauvage", "kik-piotrowski")
    assert bib.count("{Kalker1990,") == 1 and "PascalSauvage1993" in bib
    assert "10.1080/00423110701586444" in bib       # DOI printed in seed 000's references
    with pytest.raises(wr.InputError, match="no citation for method 'nonsense'"):
        wr.citation("nonsense")
    with pytest.raises(wr.InputError, match="cannot tell"):
        wr.citation(3.0)


def test_import_stays_light():
    import subprocess
    import sys

    code = ("import sys, wheelrail as wr; wr.citation('fastsim'); "
            "print(any(m in sys.modules for m in ('scipy', 'numba', 'matplotlib', 'rich')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_bibtex_covers_the_methods_own_reference_lists():
    """Every paper a method's ``references`` attribute names (by first author and year)
    has a BibTeX entry among that method's citations."""
    impls = [*wr.normal_methods().items(), *wr.tangential_methods().items()]
    for name, impl in impls:
        entries = [BIBLIOGRAPHY[k][1] for k in METHOD_REFERENCES[name]]
        for ref in impl.references:
            year = re.findall(r"\b(1[89]\d\d|20\d\d)\b", ref)[-1]
            surname = re.search(r"([A-Z][a-z]+)[,.]", ref.split(",")[0] + ",").group(1)
            assert any(e["year"] == year and surname in e["author"] for e in entries), (name, ref)
