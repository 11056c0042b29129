#!/usr/bin/env bash
# A validation campaign in N shards run by GNU parallel (on this machine's cores, or on other hosts over ssh), then
# merged into one report: the same data as one `crankcheck validate` run.
#
#   scripts/parallel-shards.sh [OPTIONS] N OUT [-- VALIDATE-ARGS...]
#
# Runs `crankcheck validate VALIDATE-ARGS --shard I/N --out SHARDS/shard-I` for I = 0..N-1 (N >= 2), then
# `crankcheck report merge SHARDS/shard-0 ... --out OUT`. VALIDATE-ARGS are validate's scenes and flags (e.g.
# `-- --quick` or `-- my_scenes/*.toml`); each shard gets `--jobs 1` unless they give --jobs, since GNU parallel
# already runs one shard per core.
#
# Options:
#   --crankcheck PATH  the program (default: build/bin/crankcheck of this checkout, else crankcheck on PATH)
#   --shards DIR       where the shard folders go (default: OUT.shards); the script creates it, or reuses one it
#                      made (shard folders are replaced by the next run, as crankcheck's output-folder rule allows)
#   --jobs J           shards at once on each host (GNU parallel's --jobs; default: one per core)
#   --sshlogin LOGINS  run the shards on other hosts (GNU parallel's --sshlogin, e.g. "node1,node2" or
#                      "8/node1,8/node2,:" where ":" is this machine). Each host needs crankcheck at the same path
#                      and must see SHARDS at the same path (a shared file system): the shards write there.
#
# Exit status: as crankcheck's (0 every comparison agrees, 1 some fail: the report is written, 2 bad input, 3 the
# environment failed). A shard that fails with 2, 3 or a signal stops the script before the merge, with that status;
# parallel's job log (SHARDS/parallel-joblog.txt) has every shard's status and time.
# Nothing here is started through a shell by crankcheck; GNU parallel composes each shard's command line with -q,
# which quotes every argument (paths with spaces or quotes are safe).
set -euo pipefail

usage() { sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; }
fail() { echo "parallel-shards.sh: $*" >&2; exit 2; }

crankcheck="" shards="" jobs="" sshlogin=""
positional=()
while (($#)); do
  case $1 in
    --crankcheck | --shards | --jobs | --sshlogin)
      (($# >= 2)) || fail "$1: needs a value"
      case $1 in
        --crankcheck) crankcheck=$2 ;;
        --shards) shards=$2 ;;
        --jobs) jobs=$2 ;;
        --sshlogin) sshlogin=$2 ;;
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
[[ -z $jobs || $jobs =~ ^[0-9]+%?$ ]] || fail "--jobs: $jobs: expected a number"
command -v parallel >/dev/null || { echo "parallel-shards.sh: GNU parallel not found (Debian: apt-get install parallel)" >&2; exit 3; }

if [[ -z $crankcheck ]]; then
  crankcheck="$(cd "$(dirname "$0")/.." && pwd)/build/bin/crankcheck"
  [[ -x $crankcheck ]] || crankcheck=$(command -v crankcheck) || fail "no crankcheck: build it or give --crankcheck"
fi
[[ -x $crankcheck ]] || fail "--crankcheck: $crankcheck: not an executable program"
# Absolute paths: the same on every host, whatever folder parallel's ssh starts in.
crankcheck=$(realpath -- "$crankcheck")
out=$(realpath -m -- "$out")
shards=$(realpath -m -- "${shards:-$out.shards}")

# The shards folder holds only what this script and crankcheck put there.
if [[ -e $shards || -L $shards ]]; then
  [[ -d $shards && ! -L $shards ]] || fail "--shards: \"$shards\": exists and is not a folder"
  for entry in "$shards"/* "$shards"/.[!.]*; do
    [[ -e $entry || -L $entry ]] || continue
    name=${entry##*/}
    [[ $name =~ ^shard-[0-9]+$ || $name == parallel-joblog.txt || $name =~ ^\.shard-[0-9]+\.crankcheck-partial- ]] ||
      fail "--shards: \"$shards\": holds \"$name\", which this script did not write; choose another folder"
  done
else
  mkdir -p -- "$shards"
fi

has_jobs=0
for arg in "${validate_args[@]}"; do [[ $arg == --jobs || $arg == --jobs=* ]] && has_jobs=1; done
((has_jobs)) || validate_args+=(--jobs 1)

parallel_args=(--will-cite --halt never --joblog "$shards/parallel-joblog.txt" --tagstring "shard {}/$n")
[[ -n $jobs ]] && parallel_args+=(--jobs "$jobs")
[[ -n $sshlogin ]] && parallel_args+=(--sshlogin "$sshlogin")
[[ -t 2 ]] && parallel_args+=(--eta)

echo "parallel-shards.sh: $n shards of: crankcheck validate ${validate_args[*]} (folders: $shards/shard-I)" >&2
status=0
parallel "${parallel_args[@]}" -q "$crankcheck" validate "${validate_args[@]}" --shard "{}/$n" --out "$shards/shard-{}" \
  ::: $(seq 0 $((n - 1))) || status=$?

# Each shard's exit status from the job log (columns: Seq Host Starttime JobRuntime Send Receive Exitval Signal
# Command); Seq is 1 + the shard's index. 0 and 1 leave the shard's data for the merge; anything else does not.
worst=0
seen=0
while IFS=$'\t' read -r seq host start runtime send receive exitval signal command; do
  [[ $seq =~ ^[0-9]+$ ]] || continue
  [[ $host == : ]] && host="this machine"
  seen=$((seen + 1))
  if ((signal != 0)); then
    echo "parallel-shards.sh: shard $((seq - 1))/$n was killed by signal $signal (host $host)" >&2
    ((worst = 128 + signal > worst ? 128 + signal : worst))
  elif ((exitval > 1)); then
    echo "parallel-shards.sh: shard $((seq - 1))/$n failed with exit status $exitval (host $host; its message is above)" >&2
    ((exitval > worst)) && worst=$exitval
  fi
done <"$shards/parallel-joblog.txt"
if ((seen != n)); then
  echo "parallel-shards.sh: GNU parallel ran $seen of $n shards (status $status); nothing merged" >&2
  exit $((worst > 0 ? worst : 3))
fi
if ((worst > 0)); then
  echo "parallel-shards.sh: nothing merged" >&2
  exit "$worst"
fi

dirs=()
for ((i = 0; i < n; ++i)); do dirs+=("$shards/shard-$i"); done
"$crankcheck" report merge "${dirs[@]}" --out "$out"
