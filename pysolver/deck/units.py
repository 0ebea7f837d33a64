"""Unit systems of the ``Units`` element.

A deck's numbers are used as written; the only conversion needed for F = m a is the force
scale: how many (mass unit * length unit / time unit^2) one force unit is. Without ``Units``
the units are consistent and the scale is 1. The names are Adams' and MotionSolve's (Adams
Solver C++'s UNITS statement, MotionSolve's Units); each value is the unit in SI units, exact
by the definitions of the inch (0.0254 m), the avoirdupois pound (0.45359237 kg) and standard
gravity (9.80665 m/s^2).
"""
_LBM, _INCH, _GN = 0.45359237, 0.0254, 9.80665
_LBF = 4.4482216152605                  # _LBM * _GN

MASS = {"KILOGRAM": 1.0, "GRAM": 1e-3, "MILLIGRAM": 1e-6, "MICROGRAM": 1e-9,
        "NANOGRAM": 1e-12, "MEGAGRAM": 1e3, "POUND_MASS": _LBM,
        "SLUG": 14.593902937206364, "SLINCH": _LBF / _INCH, "OUNCE_MASS": 0.028349523125,
        "KPOUND_MASS": 453.59237, "US_TON": 2000 * _LBM}
LENGTH = {"METER": 1.0, "MILLIMETER": 1e-3, "CENTIMETER": 1e-2, "KILOMETER": 1e3,
          "MICROMETER": 1e-6, "NANOMETER": 1e-9, "ANGSTROM": 1e-10, "INCH": _INCH,
          "MILS": 1e-3 * _INCH, "MICROINCH": 1e-6 * _INCH, "FOOT": 0.3048, "YARD": 0.9144,
          "MILE": 1609.344}
TIME = {"SECOND": 1.0, "MILLISECOND": 1e-3, "MICROSECOND": 1e-6, "NANOSECOND": 1e-9,
        "MINUTE": 60.0, "HOUR": 3600.0, "DAY": 86400.0}
FORCE = {"NEWTON": 1.0, "KILONEWTON": 1e3, "MEGANEWTON": 1e6, "CENTINEWTON": 1e-2,
         "MILLINEWTON": 1e-3, "MICRONEWTON": 1e-6, "NANONEWTON": 1e-9, "DYNE": 1e-5,
         "POUND_FORCE": _LBF, "KPOUND_FORCE": 4448.2216152605, "KILOGRAM_FORCE": _GN,
         "OUNCE_FORCE": 0.27801385095378125, "POUNDAL": _LBM * 0.3048}
TABLES = {"mass": MASS, "length": LENGTH, "time": TIME, "force": FORCE}
#: Other spellings of these units in Adams' and MotionSolve's pages (Adams' MILLISECONDS,
#: MotionSolve's KNEWTON, TONNE, MILLS, MILLIINCH and "US TON").
ALIASES = {"MILLISECONDS": "MILLISECOND", "KNEWTON": "KILONEWTON", "TONNE": "MEGAGRAM",
           "MILLS": "MILS", "MILLIINCH": "MILS", "US TON": "US_TON"}


def force_scale(mass, length, time, force):
    """Return one force unit expressed in mass*length/time^2 of the same system."""
    return FORCE[force] / (MASS[mass] * LENGTH[length] / TIME[time] ** 2)
