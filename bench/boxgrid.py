"""The benchmark scene's layout, shared by gen_scene.py and gen_mjcf.py.

N cubes of 0.2 m on the ground plane y = 0 (Y up), in a square grid of ceil(sqrt(N)) columns,
0.3 m apart centre to centre (0.1 m gaps: neighbours never touch), centred on the origin, each
released at rest with its centre at y = 0.101 m (1 mm above resting height), so every box falls,
bounces a little and then rests on four contact points.

Box i sits in row i // side, column i % side. Coordinates are whole millimetres so that the
decimal text in the scene files is exactly mm/1000, which bench/bare_ode.cpp computes as the
double nearest to mm / 1000.0 -- the same double the scene parser reads from the text.
"""
import math

SPACING_MM = 300
DROP_Y_MM = 101
SIZE = 0.2          # m, edge of a cube
DENSITY = 500.0     # kg/m^3 (4 kg per cube)
FRICTION = 0.8
BOUNCE = 0.1
MIN_BOUNCE_VEL = 0.1  # m/s (simbob's default, written out for clarity)
DT = 0.001


def side(n):
    s = math.isqrt(n)
    return s if s * s >= n else s + 1


def mm_text(mm):
    """Exact decimal text of mm/1000 (no float formatting involved)."""
    sign = "-" if mm < 0 else ""
    mm = abs(mm)
    whole, frac = divmod(mm, 1000)
    text = f"{sign}{whole}.{frac:03d}".rstrip("0").rstrip(".")
    return text if text not in ("", "-") else "0"


def boxes(n):
    """(key, x_mm, y_mm, z_mm) of every box, in creation order."""
    s = side(n)
    # (s - 1) * 300 / 2 = (s - 1) * 150 is always a whole number of millimetres.
    half = (s - 1) * (SPACING_MM // 2)
    out = []
    for i in range(n):
        row, col = divmod(i, s)
        out.append((f"Box{i}", col * SPACING_MM - half, DROP_Y_MM, row * SPACING_MM - half))
    return out
