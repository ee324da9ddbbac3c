"""``import wheelrail`` stays light: heavy dependencies load on first use."""

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


def test_cli_help_and_a_command_build_only_what_they_run():
    """``wheelrail --help`` and ``wheelrail solve --help`` do not import the solvers:
    ``build-table`` shows the table builder's defaults, which imports the exact solver,
    so a command line builds only its own sub-command's options. The full parser
    (``build_parser()``) still has every sub-command's options."""
    code = ("import sys, contextlib, io\n"
            "from wheelrail.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()) as f:\n"
            "    code = main(sys.argv[1:])\n"
            "heavy = [m for m in ('wheelrail.sweeps', 'wheelrail.tangential', 'scipy.interpolate',"
            " 'numba') if m in sys.modules]\n"
            "print(code, ','.join(heavy), 'usage: wheelrail' in f.getvalue(),"
            " '--json' in f.getvalue())")
    run = lambda *a: subprocess.run([sys.executable, "-c", code, *a], capture_output=True,  # noqa: E731
                                    text=True, check=True).stdout.split()
    assert run("--help") == ["0", "True", "False"]
    assert run("--memory-limit", "8GB", "solve", "--help") == ["0", "True", "True"]
    # the command that needs the library still gets its defaults from it
    code_bt, heavy, *_ = run("build-table", "--help")
    assert code_bt == "0" and "wheelrail.sweeps" in heavy
    from wheelrail.cli.main import COMMANDS, build_parser

    sub = next(a for a in build_parser()._actions if a.dest == "command")
    assert set(sub.choices) == {name for name, _ in COMMANDS}
    assert any("--elements" in a.option_strings for a in sub.choices["build-table"]._actions)
    assert any("--json" in a.option_strings for a in sub.choices["solve"]._actions)
