"""Reads a `mixmesh generate --report` file as TOML and checks its entries against
ranges given as KEY=LOW:HIGH (either bound may be left empty): count ranges and quality
floors, so that a mesh with the right shape but far too many or too few cells, or a
sliver, fails."""
import sys
import tomllib

path, *ranges = sys.argv[1:]
with open(path, "rb") as file:
    report = tomllib.load(file)
problems = []
for entry in ranges:
    key, bounds = entry.split("=", 1)
    low, high = bounds.split(":", 1)
    if key not in report:
        problems.append(f"no '{key}'")
        continue
    value = report[key]
    if low and value < float(low):
        problems.append(f"{key} = {value} below {low}")
    if high and value > float(high):
        problems.append(f"{key} = {value} above {high}")
for problem in problems:
    print(f"{path}: {problem}")
print("report ok" if not problems else "report wrong")
sys.exit(1 if problems else 0)
