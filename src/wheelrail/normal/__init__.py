"""Normal contact problem: the normal methods, one per module.

Hertz's closed forms (``wr.hertz``, :class:`~wheelrail.hertzian.HertzContact`) are
core types in :mod:`wheelrail.hertzian`: every method and the contact patch read them.

Each method is a frozen dataclass whose options are fields
(:mod:`wheelrail.options`); pass its registry name or a configured instance to
:func:`wheelrail.solve`::

    wr.solve(problem, creepage, mu, normal="bem")
    wr.solve(problem, creepage, mu, normal=wr.normal.Bem(element_size=2e-4))

====================  ========================  =====================================
name                  class                     module
====================  ========================  =====================================
``"hertz"``           :class:`Hertz`            :mod:`.hertz`
``"multi-hertz"``     :class:`MultiHertz`       :mod:`.multi_hertz` (Sauvage, Pascal, Ayasse)
``"linder"``          :class:`Linder`           :mod:`.linder`
``"kik-piotrowski"``  :class:`KikPiotrowski`     :mod:`.kik_piotrowski`
``"stripes"``         :class:`Stripes`          :mod:`.stripes`
``"bem"``             :class:`Bem`              :mod:`.bem` (exact half-space)
====================  ========================  =====================================

:func:`registry` (also :func:`wheelrail.normal_methods`) gives name -> class;
:func:`get` a configured instance from a name, class or instance and options.
"""

from ._base import GapProblem, NormalMethod, get, get_class, registry
from .bem import Bem, hertz_grid, solve_normal
from .hertz import Hertz
from .kik_piotrowski import KikPiotrowski
from .linder import Linder
from .multi_hertz import MultiHertz
from .stripes import Stripes

__all__ = ["NormalMethod", "GapProblem", "get", "get_class", "registry",
           "Hertz", "MultiHertz", "Linder", "KikPiotrowski", "Stripes", "Bem",
           "solve_normal", "hertz_grid"]
