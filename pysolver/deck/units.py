"""Unit systems of the ``Units`` element.

A deck's numbers are used as written; the only conversion needed for F = m a is the force
scale: how many (mass unit * length unit / time unit^2) one force unit is. Without ``Units``
the units are consistent and the scale is 1.
"""

MASS = {"KILOGRAM": 1.0, "GRAM": 1e-3, "MEGAGRAM": 1e3, "POUND_MASS": 0.45359237,
        "SLUG": 14.593902937206364, "OUNCE_MASS": 0.028349523125, "KPOUND_MASS": 453.59237}
LENGTH = {"METER": 1.0, "MILLIMETER": 1e-3, "CENTIMETER": 1e-2, "KILOMETER": 1e3,
          "INCH": 0.0254, "FOOT": 0.3048, "MILE": 1609.344}
TIME = {"SECOND": 1.0, "MILLISECOND": 1e-3, "MINUTE": 60.0, "HOUR": 3600.0}
FORCE = {"NEWTON": 1.0, "KILONEWTON": 1e3, "MILLINEWTON": 1e-3, "DYNE": 1e-5,
         "POUND_FORCE": 4.4482216152605, "KPOUND_FORCE": 4448.2216152605,
         "KILOGRAM_FORCE": 9.80665, "OUNCE_FORCE": 0.27801385095378125}
TABLES = {"mass": MASS, "length": LENGTH, "time": TIME, "force": FORCE}


def force_scale(mass, length, time, force):
    """Return one force unit expressed in mass*length/time^2 of the same system."""
    return FORCE[force] / (MASS[mass] * LENGTH[length] / TIME[time] ** 2)

