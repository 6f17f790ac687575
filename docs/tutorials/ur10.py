"""Tutorial: the sim-to-real diagnosis of a real UR10 from the IPA laser-tracker data set.

    python docs/tutorials/ur10.py [--quick] [--data DIR] [--out DIR]

The data stay where they are (``../shared/data/ipa-ur10`` beside the repository, or ``--data DIR``); nothing is
copied. ``--quick`` uses every 12th row of series C (48th of A) instead of every 2nd (12th) and 3 folds (the test
suite runs it so).
"""

# %% setup
import argparse
import sys
from pathlib import Path

parser = argparse.ArgumentParser(description="UR10 diagnosis tutorial")
parser.add_argument("--quick", action="store_true", help="fewer rows (what the test suite runs)")
parser.add_argument("--data", default=None, help="the ipa-ur10 folder (default: shared/data/ipa-ur10 above the repo)")
parser.add_argument("--out", default="tutorial_output/ur10", help="folder for the result files")
args = parser.parse_args()
STEP_C, STEP_A = (12, 48) if args.quick else (2, 12)     # use every STEP-th row of series C and A
FOLDS = 3 if args.quick else 5                           # cross-validation folds (5: the default)
REPO = Path(__file__).resolve().parents[2]

# %% find the data
def find_data(given):
    """The ipa-ur10 folder: ``--data``, else the first shared/data/ipa-ur10 above the repository."""
    if given:
        return Path(given)
    for folder in REPO.parents:
        if (folder / "shared" / "data" / "ipa-ur10").is_dir():
            return folder / "shared" / "data" / "ipa-ur10"
    sys.exit("the UR10 data folder shared/data/ipa-ur10 was not found above the repository; pass --data DIR")


DATA = find_data(args.data)

# %% convert
from tolalloc.diagnose import read_ipa_ur10  # noqa: E402  (';'-separated, decimal commas, joints in rad -> deg / mm)

C = read_ipa_ur10(DATA / "Series_C" / "measurements_random_poses.csv").iloc[::STEP_C].reset_index(drop=True)
A = read_ipa_ur10(DATA / "Series_A" / "measurements_grid.csv").iloc[::STEP_A].reset_index(drop=True)
print(f"series C: {len(C)} rows, series A: {len(A)} rows")
print(C.head(3).round(3).to_string(index=False))

# %% within a session
import tolalloc  # noqa: E402

n_train = int(0.7 * len(C))                     # row order is measurement order: the later 30 % are the test
within = tolalloc.diagnose_measurements("ur10", C.iloc[:n_train], C.iloc[n_train:], folds=FOLDS)
print(within.text())

# %% across sessions
across = tolalloc.diagnose_measurements("ur10", A, C, folds=FOLDS, test_frame="refit", register_n=30)
print(across.to_frame().to_string(index=False, float_format=lambda x: f"{x:.4f}"))
print("effect:", across.effect)
for guard in across.diagnosis.guards:
    print("GUARD:", guard[:160])

# %% save
written = within.save(Path(args.out) / "within_C", json=Path(args.out) / "within_C.json")
print("wrote", ", ".join(written))
