#!/usr/bin/env bash
# Mesh-then-deform on random wings: generates N random ordinary wings of the robustness
# suite (scripts/random-wings.py, seed SEED), then deforms each generated mesh in one
# step from the original with the motions of scripts/wing-motions.py (pitch +15 and -15
# degrees about the quarter root chord, a plunge of half the root chord, the bending
# mode with 5 degrees of tip twist), with ARA and with IDW, and judges every deformed
# mesh with the independent checker. Prints one line per wing and motion and the count
# of valid meshes.
#
#   scripts/random-wing-motions.sh N SEED [OUTDIR]
#
# MIXMESH names the program (default build/bin/mixmesh). OUTDIR (default
# build/random-wing-motions/seed-SEED) gets configs/ and one folder per wing.
set -euo pipefail

if [[ $# -lt 2 ]]; then
  echo "usage: scripts/random-wing-motions.sh N SEED [OUTDIR]" >&2
  exit 2
fi
count=$1
seed=$2
root=$(cd "$(dirname "$0")/.." && pwd)
outdir=${3:-$root/build/random-wing-motions/seed-$seed}
program=${MIXMESH:-$root/build/bin/mixmesh}
python=/usr/bin/python3
checker=$root/../shared/tools/check_mesh.py
[[ -x $program ]] || { echo "random-wing-motions: no program at $program (build first)" >&2; exit 2; }
[[ -f $checker ]] || { echo "random-wing-motions: no checker at $checker" >&2; exit 2; }

mkdir -p "$outdir/configs"
"$python" "$root/scripts/random-wings.py" "$count" "$seed" "$outdir/configs" > "$outdir/configs.txt"
valid=0
total=0
failed=()
while read -r config; do
  name=$(basename "$config" .toml)
  dir=$outdir/$name
  mkdir -p "$dir"
  if ! "$program" generate "$config" --output-dir "$dir" > "$dir/generate.log" 2>&1 < /dev/null; then
    echo "$name: generate failed: $(tail -1 "$dir/generate.log")"
    failed+=("$name generate")
    continue
  fi
  # The quarter root chord and the semi-span: from the planform keys, or from the first
  # and last stations of a cranked wing (random-wings.py writes them in order).
  if ! planform=$("$python" - "$config" <<'PYTHON'
import sys, tomllib
wing = tomllib.load(open(sys.argv[1], "rb"))["wing"]
if "station" in wing:
    root, tip = wing["station"][0], wing["station"][-1]
    print(root.get("leading_edge_x", 0.0) + 0.25 * root["chord"], root["chord"], tip["y"] - root["y"])
else:
    print(0.25 * wing["root_chord"], wing["root_chord"], wing["semi_span"])
PYTHON
  ) || ! read -r centre chord span <<< "$planform" ||
    ! "$python" "$root/scripts/wing-motions.py" "$dir/$name.vtu" "$dir/motions" "$centre" "$chord" "$span" < /dev/null \
      > "$dir/motions.log" 2>&1; then
    echo "$name: no motion files: $(tail -1 "$dir/motions.log" 2>/dev/null)"
    failed+=("$name motions")
    continue
  fi
  for motion in pitch+15 pitch-15 plunge bend; do
    for method in ara idw; do
      total=$((total + 1))
      output=$dir/${motion}_${method}.vtu
      status=ok
      if ! "$program" deform "$dir/$name.vtu" --motion "$dir/motions/${motion}_${method}.toml" -o "$output" -v \
          > "$dir/${motion}_${method}.log" 2>&1 < /dev/null; then
        status="deform failed: $(tail -1 "$dir/${motion}_${method}.log" | cut -c1-120)"
      elif ! "$python" "$checker" "$output" > "$dir/${motion}_${method}.check" 2>&1 < /dev/null; then
        status="checker: $(grep -m1 INVALID "$dir/${motion}_${method}.check" | cut -c1-120 || true)"
      fi
      figures=$(grep -m1 "step 1/1" "$dir/${motion}_${method}.log" |
        sed -E 's/.*\): ([0-9.e+-]+) s, min scaled Jacobian [0-9.e+-]+ -> ([0-9.e+-]+), wall-line angle change up to ([0-9.e+-]+) deg.*/\1 s, min s.J. \2, wall-line change \3 deg/' || true)
      if [[ $status == ok ]]; then
        valid=$((valid + 1))
        echo "$name $motion $method: valid; $figures"
      else
        echo "$name $motion $method: $status"
        failed+=("$name $motion $method")
      fi
    done
  done
done < "$outdir/configs.txt"
echo "valid: $valid of $total deformed meshes (wings that did not mesh or got no motion files count as failed below)"
if [[ ${#failed[@]} -gt 0 ]]; then
  printf 'failed: %s\n' "${failed[@]}"
  exit 1
fi
