#!/usr/bin/env bash
# The robustness suite of issue #13: N random ordinary wings (scripts/random-wings.py,
# seeded), each through `mixmesh generate` and the independent checker
# (../shared/tools/check_mesh.py, with OpenFOAM checkMesh), then one line per wing and a
# summary against the issue's quality floors.
#
#   scripts/robustness.sh N SEED [OUTDIR] [-j J] [--layers L1,L2,...] [--space ordinary|wide]
#                         [--report-only | --validity-only]
#   MIXMESH=/tmp/mixmesh-baseline scripts/robustness.sh 24 1 /tmp/robust -j 2
#
# --layers draws each wing's layer count from the list (default 24, 28, 32) and leaves
# its other parameters as they are; --space wide draws the wider design space of
# scripts/random-wings.py instead (finer surfaces, 16-48 layers: minutes per wing).
# Builds nothing: runs $MIXMESH (default build/bin/mixmesh). OUTDIR (default
# build/robustness/seed-SEED) gets configs/ and one folder per wing with log.txt (generate),
# report.toml, the .vtu, check.json, check.log and seconds.txt; summary.txt repeats the table.
# Exit status: 0 when every wing generates, checks valid and meets the floors below;
# 1 otherwise (0 with --report-only; with --validity-only the floors are reported but
# only a failed or invalid wing counts); 2 for a usage error.
set -euo pipefail

# Floors (issue #13, "Done when").
max_dihedral=175          # degrees: no tetrahedron's largest dihedral angle above this
sliver_angle=170          # degrees: ...
max_sliver_percent=0.01   # ... and at most this percentage of tetrahedra above sliver_angle
min_scaled_jacobian=1e-3  # pyramids and prisms

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
usage="usage: scripts/robustness.sh N SEED [OUTDIR] [-j J] [--layers L1,L2,...] [--space ordinary|wide] [--report-only | --validity-only]"
positional=()
jobs=1
layers=()
space=()
report_only=0
validity_only=0
while [ $# -gt 0 ]; do
  case $1 in
    -j) jobs=${2:?$usage}; shift 2 ;;
    -j*) jobs=${1#-j}; shift ;;
    --layers) layers=(--layers "${2:?$usage}"); shift 2 ;;
    --space) space=(--space "${2:?$usage}"); shift 2 ;;
    --report-only) report_only=1; shift ;;
    --validity-only) validity_only=1; shift ;;
    -h|--help) echo "$usage"; exit 0 ;;
    -*) echo "$usage" >&2; exit 2 ;;
    *) positional+=("$1"); shift ;;
  esac
done
[ ${#positional[@]} -ge 2 ] && [ ${#positional[@]} -le 3 ] || { echo "$usage" >&2; exit 2; }
count=${positional[0]}
seed=${positional[1]}
outdir=${positional[2]:-$root/build/robustness/seed-$seed}
program=${MIXMESH:-$root/build/bin/mixmesh}
checker=$root/../shared/tools/check_mesh.py
python=/usr/bin/python3
[ -x "$program" ] || { echo "robustness: $program not built (scripts/build.sh) or not executable" >&2; exit 2; }
[ -f "$checker" ] || { echo "robustness: $checker not found" >&2; exit 2; }
program=$(cd "$(dirname "$program")" && pwd)/$(basename "$program")

mkdir -p "$outdir/configs"
outdir=$(cd "$outdir" && pwd)
"$python" "$root/scripts/random-wings.py" "$count" "$seed" "$outdir/configs" "${layers[@]}" "${space[@]}" > \
  "$outdir/configs.txt"

# One wing: generate, then check the mesh if there is one. Runs in its own folder.
run_wing() {
  local config=$1 name dir start middle end generate_status=0 check_status=-
  name=$(basename "$config" .toml)
  dir=$outdir/$name
  rm -rf "$dir"
  mkdir -p "$dir"
  start=$(date +%s.%N)
  "$program" generate "$config" --output-dir "$dir" --report "$dir/report.toml" > "$dir/log.txt" 2>&1 ||
    generate_status=$?
  middle=$(date +%s.%N)
  if [ "$generate_status" -eq 0 ] && [ -f "$dir/$name.vtu" ]; then
    check_status=0
    "$python" "$checker" "$dir/$name.vtu" --json "$dir/check.json" > "$dir/check.log" 2>&1 || check_status=$?
  fi
  end=$(date +%s.%N)
  echo "$generate_status $check_status $(awk -v a="$start" -v b="$middle" -v c="$end" \
    'BEGIN { printf "%.1f %.1f", b - a, c - b }')" > "$dir/seconds.txt"
  echo "robustness: $name generate $generate_status check $check_status ($(cut -d' ' -f3,4 < "$dir/seconds.txt") s)" >&2
}
export -f run_wing
export outdir program python checker

echo "robustness: $count wings, seed $seed, $jobs at a time, $program -> $outdir" >&2
xargs -P "$jobs" -I{} bash -c 'run_wing "$1"' _ {} < "$outdir/configs.txt"

status=0
MAX_DIHEDRAL=$max_dihedral SLIVER_ANGLE=$sliver_angle MAX_SLIVER_PERCENT=$max_sliver_percent \
MIN_SCALED_JACOBIAN=$min_scaled_jacobian VALIDITY_ONLY=$validity_only "$python" - "$outdir" <<'PYTHON' | tee "$outdir/summary.txt" || status=$?
import json, math, os, re, sys

outdir = sys.argv[1]
max_dihedral = float(os.environ["MAX_DIHEDRAL"])
sliver_angle = float(os.environ["SLIVER_ANGLE"])
max_sliver_percent = float(os.environ["MAX_SLIVER_PERCENT"])
min_sj = float(os.environ["MIN_SCALED_JACOBIAN"])
types = [("tetra", "tet"), ("pyramid", "pyr"), ("wedge", "pri"), ("hexahedron", "hex")]

def first_error(text):
    for line in text.splitlines():  # the program's own error line first, then anything alarming
        if re.search(r"error:", line):
            return line.strip()
    for line in text.splitlines():
        if re.search(r"error|intersect|fail|invalid", line, re.I):
            return line.strip()
    lines = [l.strip() for l in text.splitlines() if l.strip()]
    return lines[-1] if lines else ""

def fmt(value, spec):
    return "-" if value is None else format(value, spec)

names = sorted(d for d in os.listdir(outdir) if os.path.isfile(os.path.join(outdir, d, "seconds.txt")))
rows, failed, violations = [], [], []
worst = dict(dihedral=(None, ""), nonortho=(None, ""))
worst_sj = {t: (None, "") for t, _ in types}
tets = above_170 = above_175 = 0
header = (f"{'wing':16s} {'gen':>4s} {'check':>7s} {'points':>8s} {'stop':>5s} {'dihedral':>8s} {'>170':>6s} "
          + " ".join(f"{'sJ.' + short:>9s}" for _, short in types)
          + f" {'nonorth':>7s} {'gen_s':>6s} {'chk_s':>6s}  first error")
print(header)
for name in names:
    d = os.path.join(outdir, name)
    generate_status, check_status, generate_s, check_s = open(os.path.join(d, "seconds.txt")).read().split()
    log = open(os.path.join(d, "log.txt"), errors="replace").read()
    stop = re.search(r"growth stopped early on (\d+) faces", log)
    stop = stop.group(1) if stop else "0"
    points = dihedral = nonortho = None
    n170 = "-"
    sj = {t: None for t, _ in types}
    error = ""
    ok = generate_status == "0"
    if not ok:
        error = first_error(log)
        check = "-"
    else:
        path = os.path.join(d, "check.json")
        report = json.load(open(path)) if os.path.isfile(path) else {}
        valid = report.get("valid", False)
        check = "valid" if valid else "INVALID"
        ok = valid
        if not valid:
            error = "; ".join(report.get("reasons", [])) or report.get("error", "") or first_error(
                open(os.path.join(d, "check.log"), errors="replace").read())
        points = report.get("counts", {}).get("points")
        for t, _ in types:
            q = report.get("scaled_jacobian", {}).get(t)
            if q:
                s = q.get("vtk") or q["own"]
                sj[t] = s["min"]
                if worst_sj[t][0] is None or s["min"] < worst_sj[t][0]:
                    worst_sj[t] = (s["min"], name)
        dh = report.get("tetra_dihedral")
        if dh:
            dihedral = dh["max"]
            n170 = str(dh["above_170"])
            tets += dh["count"]
            above_170 += dh["above_170"]
            above_175 += dh["above_175"]
            if worst["dihedral"][0] is None or dihedral > worst["dihedral"][0]:
                worst["dihedral"] = (dihedral, name)
        nonortho = report.get("openfoam", {}).get("max_non_orthogonality")
        if nonortho is not None and (worst["nonortho"][0] is None or nonortho > worst["nonortho"][0]):
            worst["nonortho"] = (nonortho, name)
        # Floors.
        why = []
        if dh and dh["max"] > max_dihedral:
            why.append(f"dihedral {dh['max']:.2f} > {max_dihedral:g}")
        if dh and 100.0 * dh["above_170"] / dh["count"] > max_sliver_percent:
            why.append(f"{100.0 * dh['above_170'] / dh['count']:.3f} % tets > {sliver_angle:g} deg")
        for t in ("pyramid", "wedge"):
            if sj[t] is not None and sj[t] < min_sj:
                why.append(f"{t} s.J. {sj[t]:.2e} < {min_sj:g}")
        if why:
            violations.append((name, why))
    if not ok:
        failed.append(name)
    print(f"{name:16s} {'ok' if generate_status == '0' else 'FAIL':>4s} {check:>7s} {fmt(points, 'd'):>8s} "
          f"{stop:>5s} {fmt(dihedral, '.3f'):>8s} {n170:>6s} "
          + " ".join(f"{fmt(sj[t], '.2e'):>9s}" for t, _ in types)
          + f" {fmt(nonortho, '.2f'):>7s} {float(generate_s):6.1f} {float(check_s):6.1f}  {error[:160]}")

n = len(names)
print()
print(f"pass rate: {n - len(failed)}/{n} ({100.0 * (n - len(failed)) / max(n, 1):.0f} %)"
      + (f"; failed: {' '.join(failed)}" if failed else ""))
if tets:
    print(f"worst tet dihedral: {worst['dihedral'][0]:.3f} deg ({worst['dihedral'][1]}); tets above "
          f"{sliver_angle:g} deg: {above_170} ({100.0 * above_170 / tets:.4f} %), above 175 deg: {above_175}"
          f" ({100.0 * above_175 / tets:.4f} %) of {tets}")
print("worst scaled Jacobian: " + ", ".join(
    f"{t} {fmt(worst_sj[t][0], '.3e')} ({worst_sj[t][1] or '-'})" for t, _ in types))
print(f"worst checkMesh non-orthogonality: {fmt(worst['nonortho'][0], '.3f')} ({worst['nonortho'][1] or '-'})")
print(f"floors (dihedral <= {max_dihedral:g}, <= {max_sliver_percent:g} % above {sliver_angle:g}, "
      f"pyramid/prism s.J. >= {min_sj:g}): "
      + (f"{len(violations)} of {n} wings violate" if violations else "met by every checked mesh"))
for name, why in violations:
    print(f"  {name}: {'; '.join(why)}")
sys.exit(1 if failed or (violations and os.environ["VALIDITY_ONLY"] != "1") else 0)
PYTHON
[ "$report_only" -eq 1 ] && exit 0
exit "$status"
