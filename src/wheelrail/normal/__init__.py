"""Normal contact problem: Hertz and (later) non-Hertzian methods."""

from .hertz import (HertzContact, curvatures_from_radii, hertz, hertz_coefficients,
                    hertz_from_penetration, hertz_from_radii, hertz_from_semiaxes, hertz_line)

__all__ = ["HertzContact", "hertz", "hertz_from_semiaxes", "hertz_from_radii",
           "hertz_from_penetration", "hertz_line", "curvatures_from_radii", "hertz_coefficients"]
