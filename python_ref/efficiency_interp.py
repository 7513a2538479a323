"""Off-node interpolation of the presets' efficiency tables: the fixture tests/data/efficiency_interp.csv.

    python3 python_ref/efficiency_interp.py      # write the fixture (also part `efficiency_interp` of generate.py)

Random (preset, order, sin theta_i, lambda) points interpolated by `efficiency_table.interpolate_normalised`
(the documented rule, then the per-polarisation scaling where the sum over orders exceeds 1) on the
data the crate ships: the nodes and efficiencies of src/data/efficiency_presets_data.rs, i.e. the JSON tables
rounded to `presets.RUST_DECIMALS` decimals and then to float32, as the Rust literals are read.
"""

from __future__ import annotations

import random
import sys
from pathlib import Path

sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402

import efficiency_table as et  # noqa: E402
import presets  # noqa: E402
from common import REGEN_CMD, REPO, write_csv  # noqa: E402

CSV_OUTPUT = Path("tests/data/efficiency_interp.csv")
POINTS = 2000
SEED = 20260412
# A share of the points takes any stored order (mostly evanescent ones, which must give 0); the
# others an order that propagates at the point.
ANY_ORDER_SHARE = 0.1
NAMES = ("cd", "dvd", "blazed600", "foil")


def f32(values):
    """Values as the crate stores them: rounded to float32 (from the same decimals), widened back."""
    return np.asarray(values, dtype=np.float32).astype(np.float64)


def shipped(name: str, root: Path = REPO) -> dict:
    """The preset's table as src/data/efficiency_presets_data.rs holds it."""
    t = presets.coarsen(et.read_json(root / presets.JSON_DIR / f"{name}.json"))
    c = dict(t)
    c["sin_theta_i"] = f32(t["sin_theta_i"]).tolist()
    c["lambda_nm"] = f32(t["lambda_nm"]).tolist()
    for pol in ("te", "tm"):
        c[pol] = f32(t[pol]).tolist()
    return c


def rows(root: Path = REPO) -> list[list[str]]:
    tables = {n: shipped(n, root) for n in NAMES}
    rng = random.Random(SEED)
    out = []
    for _ in range(POINTS):
        name = rng.choice(NAMES)
        t = tables[name]
        d = t["grating"]["period_nm"]
        # Slightly beyond the grids, so that the clamping is exercised.
        s = rng.uniform(-1.0, 1.0)
        lam = rng.uniform(350.0, 840.0)
        orders = list(range(t["order_min"], t["order_max"] + 1))
        prop = [m for m in orders if abs(s + m * lam / d) < 1.0]
        m = rng.choice(orders) if rng.random() < ANY_ORDER_SHARE or not prop else rng.choice(prop)
        te, tm = et.interpolate_normalised(t, m, s, lam)
        out.append([name, str(m), repr(s), repr(lam), repr(float(te)), repr(float(tm))])
    return out


def generate(out_root: Path) -> list[Path]:
    comments = [
        f"Order efficiencies of the crate's presets at {POINTS} random points (Python random.Random({SEED})):",
        "a preset, sin_theta_i uniform in [-1, 1] and lambda_nm uniform in [350, 840] nm (both slightly beyond",
        f"the grids, which clamp), and an order propagating there ({1 - ANY_ORDER_SHARE:.0%}) or any stored order.",
        "te, tm: python_ref/efficiency_table.py interpolate_normalised (the rule of docs/efficiency_tables.md,",
        "then per polarisation every order scaled by 1/sum where the sum over the stored orders exceeds 1) on the",
        f"shipped data: the JSON tables of data/efficiencies/ rounded to {presets.RUST_DECIMALS} decimals, then to float32",
        "(src/data/efficiency_presets_data.rs). Made by python_ref/efficiency_interp.py with numpy "
        f"{np.__version__}; regenerate with `{REGEN_CMD}`.",
    ]
    write_csv(out_root / CSV_OUTPUT, comments,
              ["preset", "order", "sin_theta_i", "lambda_nm", "te", "tm"], rows(REPO))
    return [CSV_OUTPUT]


if __name__ == "__main__":
    for p in generate(REPO):
        print(f"wrote {p}")
