#!/usr/bin/env bash
# A crankcheck validation campaign on a Slurm cluster: N shards as one job array, then a job that merges them.
#
#   scripts/slurm/submit.sh [OPTIONS] N OUT [-- VALIDATE-ARGS...]
#
# Submits scripts/slurm/crankcheck-array.sbatch with `sbatch --array=0-(N-1)`: task I runs
# `crankcheck validate VALIDATE-ARGS --shard I/N --out SHARDS/shard-I`; then scripts/slurm/crankcheck-merge.sbatch
# with `--dependency=afterany:ARRAY_JOB`, which runs `crankcheck report merge` of the N shard folders into OUT once
# every task has ended. VALIDATE-ARGS are validate's scenes and flags (e.g. `-- --quick`, `-- my_scenes/*.toml`).
# Logs: SHARDS/logs/shard-I.out and SHARDS/logs/merge.out. Prints the two job ids; `squeue --me` follows them.
# Exit status: 0 both jobs submitted; 2 bad input, or sbatch refused a job (its message is shown, nothing stays
# submitted: the array is cancelled if the merge is refused); 3 no sbatch.
#
# Options:
#   --crankcheck PATH  the program (default: build/bin/crankcheck of this checkout, else crankcheck on PATH)
#   --shards DIR       where the shard folders and logs go (default: OUT.shards)
#   --sbatch OPTION    one more option for both sbatch calls, e.g. --sbatch --partition=short --sbatch --time=30
#                      (repeat it; the array's tasks default to 1 CPU and 2 hours, the merge to 30 minutes)
#
# Every path must be the same on the compute nodes (a shared file system): crankcheck, scene files, SHARDS, OUT.
# The merge checks that every shard left its data; crankcheck's exit status of each job is its ExitCode in
# `scontrol show job JOB` (for a few minutes after it ends) and in Slurm's accounting (`sacct -j JOB`, where there is
# one): 0 every comparison agrees, 1 some fail (the report is still written), 2 bad input, 3 the environment failed.
set -euo pipefail

usage() { sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; }
fail() { echo "submit.sh: $*" >&2; exit 2; }

here=$(cd "$(dirname "$0")" && pwd)
crankcheck="" shards=""
sbatch_options=() positional=()
while (($#)); do
  case $1 in
    --crankcheck | --shards | --sbatch)
      (($# >= 2)) || fail "$1: needs a value"
      case $1 in
        --crankcheck) crankcheck=$2 ;;
        --shards) shards=$2 ;;
        --sbatch) sbatch_options+=("$2") ;;
      esac
      shift 2 ;;
    -h | --help) usage; exit 0 ;;
    --) shift; break ;;
    -*) fail "$1: unknown option (see --help)" ;;
    *) positional+=("$1"); shift ;;
  esac
done
validate_args=("$@")
((${#positional[@]} == 2)) || fail "expected N and OUT (see --help)"
n=${positional[0]}
out=${positional[1]}
[[ $n =~ ^[0-9]+$ ]] && ((n >= 2 && n <= 100000)) || fail "N: $n: expected a number of shards from 2 to 100000"
command -v sbatch >/dev/null || { echo "submit.sh: sbatch not found (is this a Slurm login node?)" >&2; exit 3; }
if [[ -z $crankcheck ]]; then
  crankcheck="$(cd "$here/../.." && pwd)/build/bin/crankcheck"
  [[ -x $crankcheck ]] || crankcheck=$(command -v crankcheck) || fail "no crankcheck: build it or give --crankcheck"
fi
[[ -x $crankcheck ]] || fail "--crankcheck: $crankcheck: not an executable program"
crankcheck=$(realpath -- "$crankcheck")
out=$(realpath -m -- "$out")
shards=$(realpath -m -- "${shards:-$out.shards}")
# Scene files given relatively are made absolute, so the jobs find them wherever they start (an --sbatch --chdir).
for ((i = 0; i < ${#validate_args[@]}; ++i)); do
  arg=${validate_args[i]}
  [[ $arg != -* && -e $arg ]] && validate_args[i]=$(realpath -- "$arg")
done
created=()  # the folders made here, innermost first, removed again (if still empty) when sbatch refuses the jobs
dir=$shards/logs
while [[ ! -e $dir ]]; do created+=("$dir"); dir=$(dirname -- "$dir"); done
mkdir -p -- "$shards/logs"
refused() {  # refused WHAT: sbatch printed why on stderr
  for dir in "${created[@]}"; do rmdir -- "$dir" 2>/dev/null || true; done
  fail "sbatch refused $1 (its message is above); nothing submitted"
}

array_job=$(sbatch --parsable "${sbatch_options[@]}" --array="0-$((n - 1))" --output="$shards/logs/shard-%a.out" \
  "$here/crankcheck-array.sbatch" "$crankcheck" "$n" "$shards" "${validate_args[@]}") || refused "the shards' job array"
array_job=${array_job%%;*}  # --parsable prints JOBID or JOBID;CLUSTER
merge_job=$(sbatch --parsable "${sbatch_options[@]}" --dependency="afterany:$array_job" \
  --output="$shards/logs/merge.out" "$here/crankcheck-merge.sbatch" "$crankcheck" "$n" "$shards" "$out") || {
  scancel "$array_job" || true
  refused "the merge job (the shards' job array $array_job is cancelled)"
}
merge_job=${merge_job%%;*}
echo "submit.sh: shards: job $array_job (array 0-$((n - 1))); merge: job $merge_job (after every shard) -> $out"
echo "submit.sh: logs in $shards/logs/; follow with: squeue --me;" \
  "exit codes: scontrol show job $array_job; scontrol show job $merge_job"
