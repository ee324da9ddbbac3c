"""Normal contact problem: the normal methods, one per module, and Hertz's closed forms.

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
from .hertz import (Hertz, HertzContact, curvatures_from_radii, hertz, hertz_coefficients,
                    hertz_from_penetration, hertz_from_radii, hertz_from_semiaxes, hertz_line)
from .kik_piotrowski import KikPiotrowski
from .linder import Linder
from .multi_hertz import MultiHertz
from .stripes import Stripes

__all__ = ["NormalMethod", "GapProblem", "get", "get_class", "registry",
           "Hertz", "MultiHertz", "Linder", "KikPiotrowski", "Stripes", "Bem",
           "solve_normal", "hertz_grid",
           "HertzContact", "hertz", "hertz_from_semiaxes", "hertz_from_radii",
           "hertz_from_penetration", "hertz_line", "curvatures_from_radii", "hertz_coefficients"]
