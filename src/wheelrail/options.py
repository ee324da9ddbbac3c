"""Method options declared once: typed fields with units, defaults and bounds.

Every method of wheelrail (a normal method, a creep-force law) is a frozen
dataclass whose options are fields declared with :func:`option`. The
declaration carries the type, the unit, the default, the bounds or choices and
a one-line description; construction validates every value through it, so the
API, the case files and the command line accept and refuse the same values and
every message names the option and the value (case files add the file and the
table)::

    >>> import wheelrail as wr
    >>> wr.tangential.Fastsim(nx=30)
    Fastsim(nx=30)
    >>> wr.tangential.Fastsim(nx=0)
    Traceback (most recent call last):
    ...
    wheelrail.errors.OptionError: fastsim: nx must be an integer in [1, 2000], got 0

A method is chosen by name (``"fastsim"``: the class with its defaults) or by a
configured object; :func:`resolve` turns either into an instance and
:func:`split_options` routes the keyword options of :func:`wheelrail.solve` to
the one method that declares each.

This module is part of the core layer: it imports only the base layer
(:mod:`wheelrail.errors`, :mod:`wheelrail.plausibility` for the ``typical`` /
``plausible`` ranges of options).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import numbers
from dataclasses import dataclass, field, fields
from typing import Any, Callable, ClassVar, Mapping

import numpy as np

from . import plausibility
from .errors import InputError, OptionError

__all__ = ["Option", "option", "Method", "Registry", "configured", "resolve", "method_class",
           "split_options", "describe"]

_KINDS = ("int", "float", "bool", "choice", "any")


@dataclass(frozen=True)
class Option:
    """The declaration of one option (what :func:`option` stores in a field's metadata).

    Attributes
    ----------
    kind : {"int", "float", "bool", "choice", "any"}
        Value type. ``"any"`` values are checked by ``check`` alone.
    default : object
        Default value (also valid).
    unit : str
        SI unit of the value (``""`` for dimensionless or non-numeric options).
    doc : str
        One line describing the option.
    lo, hi : float or None
        Bounds of a number (``None``: unbounded).
    lo_open, hi_open : bool
        Whether the bound itself is excluded.
    choices : tuple
        Allowed values of a ``"choice"`` option.
    allow_none : bool
        ``None`` is allowed (e.g. "not given": the method decides).
    check : callable or None
        ``check(name, value) -> value``: a further check (and normalisation)
        raising :class:`~wheelrail.errors.InputError` naming ``name`` and the
        value.
    typical : (lo, hi) or None
        The usual range of a number in wheel–rail contact: outside it a
        :class:`~wheelrail.plausibility.PlausibilityWarning` names the value and
        the likely unit slip (a length 1000 × too large: "mm given as m?").
    plausible : (lo, hi) or None
        Outside this range the value is refused
        (:class:`~wheelrail.plausibility.ImplausibleInputError`, overridable
        like every plausibility check). Both are skipped when the checks are
        switched off (:func:`wheelrail.plausibility.disabled`).
    """

    kind: str
    default: Any
    unit: str = ""
    doc: str = ""
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple = ()
    allow_none: bool = False
    check: Callable | None = None
    typical: tuple | None = None
    plausible: tuple | None = None

    def __post_init__(self):
        if self.kind not in _KINDS:
            raise ValueError(f"unknown option kind {self.kind!r}")

    # ------------------------------------------------------------ description
    def describe(self) -> str:
        """The allowed values in words (``"an integer in [1, 2000]"``, ``"one of 'a', 'b'"``)."""
        if self.kind == "bool":
            text = "true or false"
        elif self.kind == "choice":
            text = "one of " + ", ".join(map(repr, self.choices))
        elif self.kind in ("int", "float"):
            text = "an integer" if self.kind == "int" else "a number"
            text += self._range()
        else:
            text = "see the method's documentation"
        if self.allow_none and self.kind != "choice":
            text += " or None"
        return text

    def _range(self) -> str:
        lo, hi = self.lo, self.hi
        if lo is None and hi is None:
            return ""
        if hi is None:
            return f" {'>' if self.lo_open else '>='} {lo:g}"
        if lo is None:
            return f" {'<' if self.hi_open else '<='} {hi:g}"
        return (f" in {'(' if self.lo_open else '['}{lo:g}, {hi:g}"
                f"{')' if self.hi_open else ']'}")

    # ------------------------------------------------------------ validation
    def validate(self, name: str, value):
        """The checked (and normalised) value; :class:`InputError` naming ``name`` and ``value``."""
        if value is None and (self.allow_none or None in self.choices):
            return None
        if self.kind == "bool":
            if not isinstance(value, (bool, np.bool_)):
                raise InputError(f"{name} must be true or false, got {value!r}")
            value = bool(value)
        elif self.kind == "choice":
            if not _in_choices(value, self.choices):
                raise InputError(f"{name} must be {self.describe()}, got {value!r}")
        elif self.kind == "int":
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
                raise InputError(f"{name} must be {self.describe()}, got {value!r}")
            value = int(value)
            self._bounds(name, value)
        elif self.kind == "float":
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
                raise InputError(f"{name} must be {self.describe()}, got {value!r}")
            if not math.isfinite(float(value)):
                raise InputError(f"{name} must be finite, got {value!r}")
            value = float(value)
            self._bounds(name, value)
        if self.check is not None:
            out = self.check(name, value)
            value = value if out is None else out
        if (self.typical or self.plausible) and value is not None \
                and not isinstance(value, (bool, str)):
            try:  # a number, or an array of them (e.g. one speed per batch case)
                arr = np.asarray(value, dtype=float)
            except (TypeError, ValueError):
                arr = None
            if arr is not None and arr.size and np.isfinite(arr).all():
                self._plausibility(name, float(arr.min()), float(arr.max()))
        return value

    def _hint(self, v: float) -> str:
        """The likely unit mistake of a value ``v`` outside :attr:`typical`, or ""."""
        lo, hi = self.typical or (None, None)
        if lo is None or hi is None:
            return ""
        if self.unit == "m":
            if v > hi and lo <= v * 1e-3 <= hi:
                return f" (mm given as m? {v:g} mm = {v * 1e-3:g} m)"
            if v < lo and lo <= v * 1e3 <= hi:
                return f" (µm given as mm, or m as mm? {v * 1e3:g} would be usual)"
        units = {"m/s": (("km/h", 1 / 3.6), ("mm/s", 1e-3)), "s/m": (("s/km", 1e-3),)}
        if v > hi and v > 0 and self.unit in units:
            # the unit that brings the value into the usual range, else nearest to it
            def distance(f):
                return max(0.0, math.log10(v * f / hi),
                           math.log10(lo / (v * f)) if lo > 0 else 0.0)

            other, f = min(units[self.unit], key=lambda u: distance(u[1]))
            if distance(f) < math.log10(v / hi):
                return f" ({other} given as {self.unit}? {v:g} {other} = {v * f:.4g} {self.unit})"
        return ""

    def _plausibility(self, name: str, vmin: float, vmax: float | None = None) -> None:
        """Warn outside :attr:`typical`, refuse outside :attr:`plausible` (with a unit hint);
        ``vmin``, ``vmax`` the smallest and largest of the given value(s)."""
        if not plausibility.enabled():
            return
        vmax = vmin if vmax is None else vmax
        unit = f" {self.unit}" if self.unit else ""
        lo, hi = self.typical or (None, None)
        if self.plausible is not None:
            plo, phi = self.plausible
            bad = vmin if plo is not None and vmin < plo else \
                vmax if phi is not None and vmax > phi else None
            if bad is not None:
                bounds = (f"at most {phi:g}" if plo is None else f"at least {plo:g}"
                          if phi is None else f"{plo:g} … {phi:g}")
                plausibility._refuse(f"{name} = {bad:g}{unit} is not plausible for a wheel–rail "
                                     f"contact (accepted: {bounds}{unit}){self._hint(bad)}")
        if self.typical is not None:
            bad = vmin if lo is not None and vmin < lo else \
                vmax if hi is not None and vmax > hi else None
            if bad is not None:
                plausibility._warn(f"{name} = {bad:g}{unit} is outside the usual range "
                                   f"{lo:g} … {hi:g}{unit}{self._hint(bad)}")

    def _bounds(self, name, v):
        lo, hi = self.lo, self.hi
        if (lo is not None and (v <= lo if self.lo_open else v < lo)) or \
                (hi is not None and (v >= hi if self.hi_open else v > hi)):
            raise InputError(f"{name} must be {self.describe()}, got {v!r}")

    def to_dict(self) -> dict:
        """JSON-ready description (for the generated methods page)."""
        return {"kind": self.kind, "default": _plain(self.default), "unit": self.unit,
                "allowed": self.describe(), "doc": self.doc}


def _in_choices(value, choices) -> bool:
    for c in choices:
        if isinstance(c, bool) or isinstance(value, (bool, np.bool_)):
            if isinstance(c, bool) and isinstance(value, (bool, np.bool_)) and bool(value) == c:
                return True
        elif c is None:
            if value is None:
                return True
        elif isinstance(value, str) and value == c:
            return True
    return False


def _plain(v):
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, (np.generic,)):
        return v.item()
    return v


def option(default, *, kind: str | None = None, unit: str = "", doc: str = "", lo=None,
           hi=None, lo_open: bool = False, hi_open: bool = False, choices: tuple = (),
           allow_none: bool = False, check: Callable | None = None, typical=None,
           plausible=None):
    """Declare an option of a method: a dataclass field carrying its :class:`Option`.

    ``kind`` defaults from the default value (bool, int, float; a tuple of
    ``choices`` makes a choice). Example::

        nx: int = option(20, lo=1, hi=2000, doc="elements per strip")
    """
    if kind is None:
        if choices:
            kind = "choice"
        elif isinstance(default, bool):
            kind = "bool"
        elif isinstance(default, int):
            kind = "int"
        elif isinstance(default, float):
            kind = "float"
        else:
            kind = "any"
    decl = Option(kind, default, unit, doc, lo, hi, lo_open, hi_open, tuple(choices),
                  allow_none, check, None if typical is None else tuple(typical),
                  None if plausible is None else tuple(plausible))
    if default is not None or not (allow_none or None in choices):
        decl.validate("default", default)  # a declaration that refuses its own default is a bug
    return field(default=default, metadata={"option": decl})


def configured(cls):
    """Class decorator of a method: a frozen, keyword-only dataclass (options as fields).

    An unknown keyword is refused with :class:`~wheelrail.errors.InputError`
    listing the method's options (not a bare ``TypeError``).
    """
    cls = dataclass(frozen=True, kw_only=True, eq=False, repr=False)(cls)
    init = cls.__init__

    @functools.wraps(init)
    def __init__(self, *args, **kwargs):
        if args:
            raise InputError(f"{type(self).__name__} takes its options as keywords "
                             f"({', '.join(type(self).option_declarations()) or 'none'}), "
                             f"got positional argument(s) {args!r}")
        _check_known(type(self), kwargs)
        init(self, **kwargs)

    cls.__init__ = __init__
    return cls


class Method:
    """Base of every method: a frozen dataclass whose fields are its options.

    Subclasses are decorated with :func:`configured` and declare each option
    once with :func:`option`. They set the class attributes

    ``name`` : str
        The registry name (``"fastsim"``).
    ``aliases`` : tuple of str
        Other accepted names (``"she"``), case-insensitive.
    ``references`` : tuple of str
        Full citations of what the method implements (:func:`wheelrail.citation`).
    ``family`` : str
        ``"normal"`` or ``"tangential"`` (set by the family base class).

    and may override :meth:`_check` to check a combination of options.
    Construction validates every value (an :class:`~wheelrail.errors.InputError`
    names the method, the option and the value); instances are immutable —
    :meth:`replace` gives a changed copy.
    """

    name: ClassVar[str] = "abstract"
    aliases: ClassVar[tuple] = ()
    references: ClassVar[tuple] = ()
    family: ClassVar[str] = ""
    #: the family's :class:`Registry` (set on the family base class); a subclass that
    #: defines ``name`` is registered in it when it is defined
    _registry: ClassVar["Registry | None"] = None

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "name" in cls.__dict__ and cls._registry is not None:
            cls._registry.add(cls)

    def __post_init__(self):
        decls = self.option_declarations()
        for key, decl in decls.items():
            try:
                value = decl.validate(key, getattr(self, key))
            except InputError as exc:
                raise OptionError(f"{self.name}: {exc}", method=self.name, option=key,
                                  reason=str(exc)) from None
            object.__setattr__(self, key, value)
        try:
            self._check()
        except InputError as exc:
            raise OptionError(f"{self.name}: {exc}", method=self.name, reason=str(exc)) from None

    def _check(self) -> None:
        """Check a combination of options (after each single value); default: nothing."""

    # ------------------------------------------------------------ options
    @classmethod
    def option_declarations(cls) -> dict[str, Option]:
        """Option name -> :class:`Option` (type, unit, default, bounds), in declaration order."""
        if not dataclasses.is_dataclass(cls):
            return {}
        return {f.name: f.metadata["option"] for f in fields(cls) if "option" in f.metadata}

    @classmethod
    def from_options(cls, options: Mapping[str, Any] | None = None):
        """An instance from a mapping of options (a case-file table, CLI flags).

        Unknown keys are refused with the method's list of options.
        """
        options = dict(options or {})
        _check_known(cls, options)
        return cls(**options)

    def option_values(self) -> dict[str, Any]:
        """Option name -> value of this instance."""
        return {k: getattr(self, k) for k in self.option_declarations()}

    def replace(self, **changes):
        """A copy with some options changed (validated as at construction)."""
        _check_known(type(self), changes)
        return dataclasses.replace(self, **changes)

    # ------------------------------------------------------------ value semantics
    def _key(self):
        return (type(self), tuple((k, _hashable(v)) for k, v in self.option_values().items()))

    def __eq__(self, other):
        if not isinstance(other, Method):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    def __repr__(self) -> str:
        decls = self.option_declarations()
        changed = [f"{k}={getattr(self, k)!r}" for k, d in decls.items()
                   if not _same(getattr(self, k), d.default)]
        return f"{type(self).__name__}({', '.join(changed)})"


def _hashable(v):
    if isinstance(v, np.ndarray):
        return ("ndarray", v.shape, tuple(v.ravel().tolist()))
    try:
        hash(v)
    except TypeError:
        return ("id", id(v))
    return v


def _same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return False
    try:
        return bool(a == b) and type(a) is type(b)
    except Exception:  # pragma: no cover - exotic option values
        return a is b


def _check_known(cls, options: Mapping) -> None:
    allowed = cls.option_declarations()
    unknown = sorted(set(options) - set(allowed))
    if unknown:
        family = f"{cls.family} " if cls.family else ""
        reason = (f"unknown option(s) {', '.join(unknown)} of {family}method {cls.name!r}; "
                  f"its options: {', '.join(allowed) or 'none'}")
        raise OptionError(f"{family}method {cls.name!r} does not accept option(s) "
                          f"{', '.join(unknown)}; its options: {', '.join(allowed) or 'none'}",
                          method=cls.name, option=unknown[0], reason=reason)


class Registry:
    """Name (and alias, lower case) -> class of one method family.

    The family base class holds one (``_registry``); every subclass that
    defines ``name`` is added when it is defined (:meth:`Method.__init_subclass__`).
    """

    def __init__(self, family: str):
        self.family = family
        self._by_key: dict[str, type] = {}

    def add(self, cls) -> None:
        for key in (cls.name, *cls.aliases):
            taken = self._by_key.get(key.lower(), cls)
            if taken is not cls:
                raise TypeError(f"{self.family} method name {key!r} is taken by "
                                f"{taken.__name__}")
            self._by_key[key.lower()] = cls

    def classes(self) -> dict[str, type]:
        """Registry name -> class, sorted by name (no aliases)."""
        return {c.name: c for c in sorted(set(self._by_key.values()), key=lambda c: c.name)}

    def get(self, spec, base: type, options=None, *, argname: str = "method"):
        """A configured instance from a name, class or instance (:func:`resolve`)."""
        return resolve(spec, base, self._by_key, options, argname=argname)

    def get_class(self, spec, base: type, *, argname: str = "method") -> type:
        """The class of a method given by name, class or instance (:func:`method_class`)."""
        return method_class(spec, base, self._by_key, argname=argname)


def method_class(spec, base: type, registry: Mapping[str, type], *, argname: str = "method"):
    """The class of a method given by name (or alias), class or instance."""
    if isinstance(spec, base):
        return type(spec)
    if isinstance(spec, type) and issubclass(spec, base):
        return spec
    if not isinstance(spec, str):
        raise InputError(f"{argname} must be a method name or a {base.__name__}, got {spec!r}")
    cls = registry.get(spec.lower())
    if cls is None:
        names = sorted({c.name for c in registry.values()})
        what = {"normal": "normal method", "tangential": "creep-force method"}.get(
            base.family, "method")
        raise InputError(f"unknown {what} {spec!r} ({argname}=); choose one of "
                         f"{', '.join(names)}")
    return cls


def resolve(spec, base: type, registry: Mapping[str, type], options: Mapping | None = None,
            *, argname: str = "method"):
    """An instance of ``base`` from a name, a class or an instance, with ``options`` applied.

    Parameters
    ----------
    spec : str, type or Method
        A registry name or alias (case-insensitive; the class with its defaults
        and ``options``), a subclass of ``base`` or a configured instance.
    base : type
        The family's base class.
    registry : mapping
        Name (and alias) -> class.
    options : mapping, optional
        Options to set (on an instance: :meth:`Method.replace`).
    argname : str
        The argument's name in messages.
    """
    options = dict(options or {})
    if isinstance(spec, base):
        return spec.replace(**options) if options else spec
    return method_class(spec, base, registry, argname=argname).from_options(options)


def split_options(normal: type, tangential: type, options: Mapping) -> tuple[dict, dict]:
    """Route keyword options to the one of two method classes that declares each.

    An option declared by neither, or by both, is an error naming both methods
    and their options.
    """
    n_decl, t_decl = normal.option_declarations(), tangential.option_declarations()
    nopts, topts = {}, {}
    for k, v in options.items():
        n_ok, t_ok = k in n_decl, k in t_decl
        if n_ok == t_ok:
            why = "both" if n_ok else "neither"
            raise InputError(
                f"option {k!r} belongs to {why} of normal method {normal.name!r} (options: "
                f"{', '.join(n_decl) or 'none'}) and tangential method {tangential.name!r} "
                f"(options: {', '.join(t_decl) or 'none'})"
                + ("; configure the method that should take it, e.g. "
                   f"normal=wheelrail.normal.{normal.__name__}({k}=...)" if n_ok else ""))
        (nopts if n_ok else topts)[k] = v
    return nopts, topts


def describe(cls) -> str:
    """Markdown description of a method class: name, options (unit, default, allowed
    values, meaning) and references — generated from the declarations, so that the
    documentation cannot drift from the code (the docs' methods page is made of these)."""
    doc = (cls.__doc__ or "").strip().split("\n\n")[0].replace("\n", " ")
    lines = [f"### `{cls.name}` — `{cls.__module__.rsplit('.', 1)[0]}.{cls.__name__}`", "",
             doc, ""]
    if cls.aliases:
        lines += ["Also accepted: " + ", ".join(f"`{a}`" for a in cls.aliases) + ".", ""]
    decls = cls.option_declarations()
    if decls:
        lines += ["| option | unit | default | allowed | meaning |", "|---|---|---|---|---|"]
        for name, d in decls.items():
            default = "`None`" if d.default is None else f"`{d.default!r}`"
            lines.append(f"| `{name}` | {d.unit or '–'} | {default} | {d.describe()} | "
                         f"{d.doc} |")
    else:
        lines.append("No options.")
    if cls.references:
        lines += ["", "References:", ""] + [f"- {r}" for r in cls.references]
    return "\n".join(lines) + "\n"

