#!/usr/bin/env bash
# A batch as a Slurm job array on the real scheduler, against the same batch run
# locally two at a time:
#
#   array_matches_local.sh MIXMESH CONFIG FAILING_CONFIG FOLDER
#
# dry run (files only, nothing queued), submit, wait with squeue, the array's sacct
# lines, collect, and the summaries compared on the columns that do not depend on the
# machine (case, status, points, cells, scaled Jacobians); then resubmitting runs
# nothing, and after one case's result is removed it runs that case alone. A config
# that fails while meshing, submitted beside, must show in sacct as FAILED and in
# its summary with its error line.
set -euo pipefail
program=$1
config=$2
failing_config=$3
folder=$4
cluster=$folder/cluster
rm -rf "$folder"
mkdir -p "$folder"

fail() {
  echo "FAILED: $*"
  exit 1
}

# Waits until the job has left the queue and its tasks are in the accounting.
wait_for_job() {
  local job=$1 tasks=$2
  for _ in $(seq 600); do
    if [ -z "$(squeue --noheader --job "$job" 2> /dev/null)" ] \
      && [ "$(sacct --noheader --allocations --jobs "$job" --format=State | grep -Evc 'PENDING|RUNNING|^ *$')" -ge "$tasks" ]; then
      return 0
    fi
    sleep 1
  done
  fail "job $job still queued after 600 s"
}

# Submits CONFIG into FOLDER and prints the job id (nothing when nothing was submitted).
submit() {
  local output
  output=$("$program" batch "$@")
  echo "$output" >&2
  sed -n 's/.*submitted job \([0-9][0-9]*\).*/\1/p' <<< "$output"
}

# Summary columns 1-10: case, status, points, cells by type, min scaled Jacobian,
# deformed meshes and their min scaled Jacobian (not seconds or memory).
deterministic() { cut -d, -f1-10 "$1" | sort; }

start=$(date +%s)
"$program" batch "$config" --slurm "$cluster" --dry-run --time 15
grep -qx '#SBATCH --array=0-3%2' "$cluster/array.sh" || fail "dry run: no --array=0-3%2 line in array.sh"
grep -qx '#SBATCH --time=15' "$cluster/array.sh" || fail "dry run: --time 15 did not override [slurm] time"
[ "$(grep -vc '^#' "$cluster/manifest.tsv")" -eq 4 ] || fail "dry run: the manifest does not list 4 cases"
[ -z "$(squeue --noheader --name "mixmesh-cluster")" ] || fail "dry run: a job was queued"

job=$(submit "$config" --slurm "$cluster")
[ -n "$job" ] || fail "no job id from the submission"
failing_job=$(submit "$failing_config" --slurm "$folder/failing")
wait_for_job "$job" 4
echo "sacct of job $job:"
sacct --jobs "$job" --allocations --format=JobID,JobName%20,State,ExitCode,Elapsed
[ "$(sacct --noheader --allocations --jobs "$job" --format=State | grep -c COMPLETED)" -eq 4 ] \
  || fail "not every task of job $job completed"

"$program" batch --collect "$cluster"
"$program" batch "$config" -j 2 -o "$folder/local" > "$folder/local.log"
echo "summary of the array:"
cat "$cluster/summary.csv"
echo "summary of the local run (-j 2):"
cat "$folder/local/summary.csv"
diff <(deterministic "$cluster/summary.csv") <(deterministic "$folder/local/summary.csv") \
  || fail "the array's summary differs from the local run's"
[ "$(grep -c ',ok,' "$cluster/summary.csv")" -eq 4 ] || fail "not 4 cases ok"

wait_for_job "$failing_job" 1
sacct --jobs "$failing_job" --allocations --format=JobID,JobName%20,State,ExitCode,Elapsed
sacct --noheader --allocations --jobs "$failing_job" --format=State,ExitCode | grep -q 'FAILED *1:0' \
  || fail "the failing case is not FAILED with exit code 1 in sacct"
status=0
"$program" batch --collect "$folder/failing" || status=$?
[ "$status" -eq 1 ] || fail "collecting one failed case exits with $status, not 1"
grep -q ',failed (exit 1),.*,"mixmesh: error: .*stay inverted' "$folder/failing/summary.csv" \
  || fail "the failed case's summary line has no error line"

[ -z "$(submit "$config" --slurm "$cluster")" ] || fail "a complete batch was submitted again"
third=$(grep -v '^#' "$cluster/manifest.tsv" | sed -n 3p | cut -f1)
rm "$cluster/$third/task.toml"
job=$(submit "$config" --slurm "$cluster")
grep -qx '#SBATCH --array=2%2' "$cluster/array.sh" || fail "the resubmission does not run case 2 alone"
wait_for_job "$job" 1
"$program" batch --collect "$cluster"
diff <(deterministic "$cluster/summary.csv") <(deterministic "$folder/local/summary.csv") \
  || fail "the resumed array's summary differs from the local run's"
echo "slurm array matches the local batch ($(($(date +%s) - start)) s)"
