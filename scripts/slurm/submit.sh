#!/usr/bin/env bash
# A crankcheck validation campaign on a Slurm cluster: N shards as one job array, then a job that merges them.
#
#   scripts/slurm/submit.sh [OPTIONS] N OUT [-- VALIDATE-ARGS...]
#
# Submits scripts/slurm/crankcheck-array.sbatch with `sbatch --array=0-(N-1)`: task I runs
# `crankcheck validate --shard I/N --out SHARDS/shard-I VALIDATE-ARGS`; then scripts/slurm/crankcheck-merge.sbatch
# with `--dependency=afterany:ARRAY_JOB`, which runs `crankcheck report merge` of the N shard folders into OUT once
# every task has ended. N is a number from 2 to 100000. VALIDATE-ARGS are validate's scenes and flags (e.g.
# `-- --quick`, `-- my_scenes/*.toml`), given to crankcheck as they are: both jobs run in the folder submit.sh was
# started in (sbatch --chdir), so relative scene paths mean what they mean here; with an `--sbatch --chdir=DIR` of
# your own they are relative to DIR instead.
# Logs: SHARDS/logs/shard-I.out and SHARDS/logs/merge.out. Prints the two job ids; `squeue --me` follows them.
# Exit status: 0 both jobs submitted; 2 bad input, or sbatch refused a job (its message is shown, nothing stays
# submitted: the array is cancelled if the merge is refused); 3 no sbatch.
#
# Options:
#   --crankcheck PATH  the program (default: build/bin/crankcheck of this checkout, else crankcheck on PATH)
#   --shards DIR       where the shard folders and logs go (default: OUT.shards); submit.sh creates it, or reuses one
#                      that holds only what it and crankcheck wrote (shard-I folders, logs/ with their logs)
#   --sbatch OPTION    one more option for both sbatch calls, as one word with its value, e.g.
#                      --sbatch --partition=short --sbatch --time=30 (repeat it; the array's tasks default to 1 CPU
#                      and 2 hours, the merge to 30 minutes)
#
# Refused (exit status 2, one line naming the argument, before anything is created or submitted):
#   - N other than a number from 2 to 100000; an empty OUT or --shards; SHARDS and OUT the same folder or one
#     inside the other; a SHARDS folder holding anything submit.sh did not write; a SHARDS path with a backslash
#     (Slurm reads a backslash in a log's path as "no %-patterns", and each task's log needs one);
#   - in VALIDATE-ARGS (before a `--` of their own): --out and --shard (submit.sh sets them for each task),
#     --profile (one file that every task would write: profile one shard with `crankcheck validate --shard I/N
#     --profile FILE` instead), and -h/--help (ask `crankcheck validate --help`);
#   - by crankcheck itself (`crankcheck validate --check`: its own line and status), OUT a folder its rule does not
#     let it replace (one of yours), a scene or a flag of VALIDATE-ARGS that it refuses;
#   - an --sbatch value that is not an option (a word not starting with -, which sbatch would take for the script),
#     and the options submit.sh sets itself: --array/-a, --dependency/-d, --output/-o, --error/-e, --wrap.
# No path or flag given here is read by sbatch or Slurm as a pattern or a command: every % in the log paths given
# to sbatch --output is written %% (Slurm's filename patterns), and the program, N, the folders and VALIDATE-ARGS
# reach the batch scripts as their arguments, which Slurm passes unchanged (no environment variable carries them).
#
# Every path must be the same on the compute nodes (a shared file system): crankcheck, scene files, this folder,
# SHARDS, OUT. The merge checks that every shard left its data; crankcheck's exit status of each job is its ExitCode in
# `scontrol show job JOB` (for a few minutes after it ends) and in Slurm's accounting (`sacct -j JOB`, where there is
# one): 0 every comparison agrees, 1 some fail (the report is still written), 2 bad input, 3 the environment failed.
set -euo pipefail

usage() { sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; }
fail() { echo "submit.sh: $*" >&2; exit 2; }

here=$(cd "$(dirname "$0")" && pwd)
crankcheck="" shards="" shards_given=0
sbatch_options=() positional=()
while (($#)); do
  case $1 in
    --crankcheck | --shards | --sbatch)
      (($# >= 2)) || fail "$1: needs a value"
      case $1 in
        --crankcheck) crankcheck=$2 ;;
        --shards) shards=$2 shards_given=1 ;;
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
[[ $n =~ ^[0-9]{1,6}$ ]] && n=$((10#$n)) && ((n >= 2 && n <= 100000)) ||
  fail "N: $n: expected a number of shards from 2 to 100000"
[[ -n $out ]] || fail "OUT: empty: expected the merged report's folder"
((!shards_given)) || [[ -n $shards ]] || fail "--shards: empty: expected a folder"
# VALIDATE-ARGS: the flags submit.sh sets itself, or that every task would act on alike (up to their own `--`, after
# which crankcheck reads every word as a scene).
for arg in "${validate_args[@]}"; do
  case $arg in
    --) break ;;
    --out | --out=*) fail "VALIDATE-ARGS: --out: submit.sh gives each shard its own (OUT is the merged report)" ;;
    --shard | --shard=*) fail "VALIDATE-ARGS: --shard: submit.sh gives each shard its own part (N)" ;;
    --profile | --profile=*)
      fail "VALIDATE-ARGS: --profile: every shard would write the one FILE; profile one shard by hand instead" \
        "(crankcheck validate --shard I/N --profile FILE ...)" ;;
    -h | --help) fail "VALIDATE-ARGS: $arg: see crankcheck validate --help" ;;
  esac
done
# --sbatch: options only (sbatch takes its first other word for the script), and none of those submit.sh sets (a
# long one also as the abbreviation sbatch accepts, a short one also with its value attached).
for option in "${sbatch_options[@]}"; do
  [[ $option == -?* && $option != -- ]] || fail "--sbatch: \"$option\": not an option (give an option and its value as one word: --sbatch --partition=short)"
  if [[ $option == --* ]]; then
    name=${option%%=*}
    for own in array dependency output error wrap; do
      [[ ${#name} -gt 2 && --$own == "$name"* ]] &&
        fail "--sbatch: $option: submit.sh sets --array, --dependency, --output, --error itself (and takes no --wrap)"
    done
  elif [[ $option == -[adoe]* ]]; then
    fail "--sbatch: $option: submit.sh sets --array, --dependency, --output, --error itself"
  fi
done
command -v sbatch >/dev/null || { echo "submit.sh: sbatch not found (is this a Slurm login node?)" >&2; exit 3; }
if [[ -z $crankcheck ]]; then
  crankcheck="$(cd "$here/../.." && pwd)/build/bin/crankcheck"
  [[ -x $crankcheck ]] || crankcheck=$(command -v crankcheck) || fail "no crankcheck: build it or give --crankcheck"
fi
[[ -f $crankcheck && -x $crankcheck ]] || fail "--crankcheck: $crankcheck: not an executable program"
crankcheck=$(realpath -- "$crankcheck") || fail "--crankcheck: $crankcheck: no absolute path"
workdir=$(pwd -P) || fail "the current folder: no absolute path"
out=$(realpath -m -- "$out") || fail "OUT: $out: no absolute path"
shards=$(realpath -m -- "${shards:-$out.shards}") || fail "--shards: $shards: no absolute path"
[[ $shards != "$out" && $shards/ != "$out"/* && $out/ != "$shards"/* ]] ||
  fail "--shards: \"$shards\": the same folder as OUT \"$out\", or one inside the other"
[[ $shards != *\\* ]] ||
  fail "--shards: \"$shards\" (--shards, by default OUT.shards): has a backslash, which turns off the %a of each" \
    "task's log path in Slurm; choose another folder"
# OUT, the scenes and the flags are checked by crankcheck's own rules before anything is submitted (a folder of the
# user's as OUT let every task run, then the merge refused it); as a shard, so that this node needs no gnuplot (the
# merge job draws the figures), from the folder the jobs start in (an --sbatch --chdir=DIR of the user's: DIR, where
# relative scenes then are). `validate --check` runs and creates nothing.
checkdir=$workdir
for option in "${sbatch_options[@]}"; do [[ $option == --chdir=* ]] && checkdir=${option#--chdir=}; done
(cd -- "$checkdir" && exec "$crankcheck" validate --check --shard "0/$n" --out "$out" "${validate_args[@]}") >/dev/null ||
  exit $?
# The shards folder holds only what submit.sh and crankcheck put there (Slurm truncates the logs it is given).
if [[ -e $shards || -L $shards ]]; then
  [[ -d $shards && ! -L $shards ]] || fail "--shards: \"$shards\": exists and is not a folder"
  for entry in "$shards"/* "$shards"/.[!.]* "$shards"/logs/* "$shards"/logs/.[!.]*; do
    [[ -e $entry || -L $entry ]] || continue
    name=${entry#"$shards"/}
    if [[ $name == logs ]]; then
      [[ -d $entry && ! -L $entry ]] || fail "--shards: \"$shards\": its \"logs\" is not a folder submit.sh made"
    elif [[ $name =~ ^logs/(shard-[0-9]+|merge)\.out$ ]]; then
      [[ -f $entry && ! -L $entry ]] || fail "--shards: \"$shards\": its \"$name\" is not a log Slurm wrote"
    else
      [[ $name =~ ^shard-[0-9]+$ || $name =~ ^\.shard-[0-9]+\.crankcheck-partial- ]] ||
        fail "--shards: \"$shards\": holds \"$name\", which submit.sh did not write; choose another folder"
    fi
  done
fi
created=()  # the folders made here, innermost first, removed again (if still empty) when sbatch refuses the jobs
dir=$shards/logs
while [[ ! -e $dir ]]; do created+=("$dir"); dir=$(dirname -- "$dir"); done
mkdir -p -- "$shards/logs"
refused() {  # refused WHAT: sbatch printed why on stderr
  for dir in "${created[@]}"; do rmdir -- "$dir" 2>/dev/null || true; done
  fail "sbatch refused $1 (its message is above); nothing submitted"
}

# The log paths as Slurm's filename patterns: every % written %% (a backslash is refused above). --chdir comes before
# the --sbatch options, so that an --sbatch --chdir of the user's is the one that counts.
logs=${shards//%/%%}/logs
array_job=$(sbatch --parsable --chdir="$workdir" "${sbatch_options[@]}" --array="0-$((n - 1))" \
  --output="$logs/shard-%a.out" "$here/crankcheck-array.sbatch" "$crankcheck" "$n" "$shards" "${validate_args[@]}") ||
  refused "the shards' job array"
array_job=${array_job%%;*}  # --parsable prints JOBID or JOBID;CLUSTER
merge_job=$(sbatch --parsable --chdir="$workdir" "${sbatch_options[@]}" --dependency="afterany:$array_job" \
  --output="$logs/merge.out" "$here/crankcheck-merge.sbatch" "$crankcheck" "$n" "$shards" "$out") || {
  scancel "$array_job" || true
  refused "the merge job (the shards' job array $array_job is cancelled)"
}
merge_job=${merge_job%%;*}
echo "submit.sh: shards: job $array_job (array 0-$((n - 1))); merge: job $merge_job (after every shard) -> $out"
echo "submit.sh: logs in $shards/logs/; follow with: squeue --me;" \
  "exit codes: scontrol show job $array_job; scontrol show job $merge_job"
