"""Reads a `mixmesh generate --report` file as TOML and checks its [[deform]] tables:
as many as `deformed_meshes` says, one per expected file stem, each mesh valid."""
import sys
import tomllib

path, *stems = sys.argv[1:]
with open(path, "rb") as file:
    report = tomllib.load(file)
tables = report.get("deform", [])
problems = []
if report.get("deformed_meshes") != len(tables):
    problems.append(f"deformed_meshes = {report.get('deformed_meshes')} but {len(tables)} [[deform]] tables")
if [table["file_stem"] for table in tables] != stems:
    problems.append(f"file stems {[table['file_stem'] for table in tables]}, expected {stems}")
for table in tables:
    if not table["min_scaled_jacobian"] > 0.0 or not table["largest_displacement"] > 0.0:
        problems.append(f"{table['file_stem']}: min scaled Jacobian {table['min_scaled_jacobian']}, "
                        f"largest displacement {table['largest_displacement']}")
smallest = min((table["min_scaled_jacobian"] for table in tables), default=None)
if report.get("deformed_min_scaled_jacobian") != smallest:
    problems.append(f"deformed_min_scaled_jacobian {report.get('deformed_min_scaled_jacobian')}, "
                    f"smallest of the tables {smallest}")
for problem in problems:
    print(f"{path}: {problem}")
print("report ok" if not problems else "report wrong")
sys.exit(1 if problems else 0)
