"""``import wheelrail`` stays light: heavy dependencies load on first use (issue 2, item 1)."""

import subprocess
import sys


def test_import_does_not_load_heavy_dependencies():
    code = ("import sys, wheelrail; "
            "heavy = [m for m in ('scipy', 'numba', 'matplotlib', 'xarray', 'rich') "
            "if m in sys.modules]; print(','.join(heavy))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_lazy_names_resolve():
    import wheelrail as wr

    for name in ("profiles", "geometry", "halfspace", "Wheelset", "contact_table",
                 "solve_normal", "solve_gap", "kalker_coefficients", "solve_creepages",
                 "load_case", "subsurface_stresses"):
        assert getattr(wr, name) is not None
