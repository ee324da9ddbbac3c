"""Reading case files: the entry points, and single-contact cases (``[contact]``)."""

from __future__ import annotations

from types import MappingProxyType
from typing import Mapping

from ..contact import Case
from ..wheelset import WheelsetCase
from ...errors import CaseFileError, InputError
from ...plausibility import check_creepage
from ._reader import (
    Reader,
    check_plausible,
    read_contact,
    read_forces,
    read_friction,
    read_materials,
    read_methods,
    read_toml,
)
from .wheelset import is_wheelset_case, wheelset_case_from_dict

__all__ = ["load_case", "case_from_dict", "load_contact_case", "load_wheelset_case"]

_TOP_TABLES = ("material", "contact", "creepage", "friction", "method", "force")

def load_case(path_or_str):
    """Read and validate a case file: a single contact or a wheelset on a track.

    Parameters
    ----------
    path_or_str : str or os.PathLike
        A path to a ``.toml`` file, or the TOML text itself (a string that
        contains a newline or ``=`` is taken as text).

    Returns
    -------
    Case or WheelsetCase
        A :class:`WheelsetCase` when the file has a ``[wheelset]``, ``[track]``,
        ``[motion]`` or ``[position]`` table.

    Raises
    ------
    CaseFileError
        Unreadable file, malformed TOML (with line and column), unknown table
        or key, or an invalid value; the message names file, table, key and
        value.

    Examples
    --------
    >>> case = load_case('''
    ... [contact]
    ... Fn = 7500.0
    ... A = 1.0869565
    ... B = 1.6666667
    ... [friction]
    ... mu = 0.3
    ... [method]
    ... tangential = "linear"
    ... ''')
    >>> case.mu, case.tangential
    (0.3, Linear())
    """
    data, source = read_toml(path_or_str)
    return case_from_dict(data, source=source)



def case_from_dict(data: Mapping, source: str = "<dict>"):
    """Validate a parsed case (the dictionary ``tomllib`` returns).

    Returns a :class:`Case` (a single contact, ``[contact]``) or a
    :class:`WheelsetCase` (``[wheelset]``, ``[track]``, ``[motion]``, ``[position]``).
    """
    r = Reader(source)
    if not isinstance(data, Mapping):
        raise CaseFileError(f"{source}: a case must be a table, got {type(data).__name__}")
    if is_wheelset_case(data):
        return wheelset_case_from_dict(r, data)
    r.unknown("", data, _TOP_TABLES)
    for name in _TOP_TABLES:
        if name in data and not isinstance(data[name], Mapping):
            raise CaseFileError(f"{source}: '{name}' must be a table [{name}], got {data[name]!r}")

    materials = read_materials(r, data.get("material", {}))
    contact = read_contact(r, r.required_table(data, "contact"))
    cr = data.get("creepage", {})
    r.unknown("creepage", cr, ("xi", "eta", "phi"))
    creepage = tuple(r.number("creepage", cr, k, default=0.0) for k in ("xi", "eta", "phi"))
    for k, v in zip(("xi", "eta", "phi"), creepage):
        check_plausible(r, "creepage", k, v, lambda v, k=k: check_creepage(**{k: v}))
    mu = read_friction(r, data)
    normal, tangential, methods = read_methods(r, data.get("method", {}))
    forces = read_forces(r, data.get("force", {}), contact.Fn, mu)
    case = Case(materials=materials, contact=contact, creepage=creepage, mu=mu, normal=normal,
                tangential=tangential, methods=MappingProxyType(methods),
                forces=MappingProxyType(forces), source=source)
    try:  # catch radii that do not form a convex contact etc. now, with the table named
        case.hertz_contact
    except InputError as exc:
        raise CaseFileError(f"{source}: [contact]: {exc}") from None
    return case


def load_contact_case(path_or_str) -> Case:
    """Read and validate a single-contact case file (``[contact]``; see :func:`load_case`)."""
    case = load_case(path_or_str)
    if isinstance(case, WheelsetCase):
        raise CaseFileError(f"{case.source}: this is a wheelset case ([wheelset], [track], "
                            "[motion], [position]); run it with 'wheelrail wheelset'")
    return case


def load_wheelset_case(path_or_str) -> WheelsetCase:
    """Read and validate a wheelset case file (see :func:`load_case`)."""
    case = load_case(path_or_str)
    if not isinstance(case, WheelsetCase):
        raise CaseFileError(f"{case.source}: not a wheelset case: it has no [wheelset], "
                            "[track], [motion] and [position] tables (run it with "
                            "'wheelrail solve')")
    return case
