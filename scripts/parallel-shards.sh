#!/usr/bin/env bash
# A validation campaign in N shards run by GNU parallel (on this machine's cores, or on other hosts over ssh), then
# merged into one report: the same data as one `crankcheck validate` run.
#
#   scripts/parallel-shards.sh [OPTIONS] N OUT [-- VALIDATE-ARGS...]
#
# Runs `crankcheck validate --shard I/N --out SHARDS/shard-I VALIDATE-ARGS` for I = 0..N-1 (N from 2 to 100000),
# then `crankcheck report merge SHARDS/shard-0 ... --out OUT`. VALIDATE-ARGS are validate's scenes and flags (e.g.
# `-- --quick` or `-- my_scenes/*.toml`); each shard gets `--jobs 1` unless they give --jobs, since GNU parallel
# already runs one shard per core. Every shard runs in the folder this script was started in, so relative scene
# paths mean what they mean here (on other hosts too: see --sshlogin).
#
# Options:
#   --crankcheck PATH  the program (default: build/bin/crankcheck of this checkout, else crankcheck on PATH)
#   --shards DIR       where the shard folders go (default: OUT.shards); the script creates it, or reuses one it
#                      made (shard folders are replaced by the next run, as crankcheck's output-folder rule allows)
#   --jobs J           shards at once on each host (GNU parallel's --jobs: a number, or a percentage of the cores
#                      such as 50%; default: one per core)
#   --sshlogin LOGINS  run the shards on other hosts (GNU parallel's --sshlogin, given to it as it is, e.g.
#                      "node1,node2" or "8/node1,8/node2,:" where ":" is this machine). Each host needs bash and
#                      crankcheck at the same path, and must see SHARDS and this folder at the same paths (a shared
#                      file system): the shards read their arguments from SHARDS and write there.
#
# Refused (exit status 2, one line naming the argument, before anything is created or run):
#   - N other than a number from 2 to 100000; an empty OUT or --shards; SHARDS and OUT the same folder or one
#     inside the other; a --shards folder that holds anything this script did not write;
#   - in VALIDATE-ARGS (before a `--` of their own): --out and --shard (the script sets them for each shard),
#     --profile (one file that every shard would write: profile one shard with `crankcheck validate --shard I/N
#     --profile FILE` instead), and -h/--help (ask `crankcheck validate --help`);
#   - then, by crankcheck itself (`crankcheck validate --check`: its own line and status), OUT a folder its rule
#     does not let it replace (one of yours), a scene or a flag of VALIDATE-ARGS that it refuses.
# No path, scene name or flag given here is ever read by GNU parallel, nor by any shell, as a command or as a
# template: GNU parallel runs only a fixed command (bash reading SHARDS/validate-args, where this script writes the
# program, the working folder and VALIDATE-ARGS as NUL-separated words, then running crankcheck with them as they
# are) with the shard's number as its one argument. Names with spaces, quotes, newlines, `{}`, `{= ... =}`, `:::`
# or a leading `-` (after `--`, or as ./-name) reach crankcheck unchanged.
#
# Exit status: as crankcheck's (0 every comparison agrees, 1 some fail: the report is written, 2 bad input, 3 the
# environment failed). A shard that fails with 2, 3 or a signal stops the script before the merge, with that status;
# parallel's job log (SHARDS/parallel-joblog.txt) has every shard's status and time.
set -euo pipefail

usage() { sed -n '2,/^set -euo/{/^#/s/^# \{0,1\}//p}' "$0"; }
fail() { echo "parallel-shards.sh: $*" >&2; exit 2; }

crankcheck="" shards="" shards_given=0 jobs="" sshlogin=""
positional=()
while (($#)); do
  case $1 in
    --crankcheck | --shards | --jobs | --sshlogin)
      (($# >= 2)) || fail "$1: needs a value"
      case $1 in
        --crankcheck) crankcheck=$2 ;;
        --shards) shards=$2 shards_given=1 ;;
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
[[ $n =~ ^[0-9]{1,6}$ ]] && n=$((10#$n)) && ((n >= 2 && n <= 100000)) ||
  fail "N: $n: expected a number of shards from 2 to 100000"
[[ -n $out ]] || fail "OUT: empty: expected the merged report's folder"
((!shards_given)) || [[ -n $shards ]] || fail "--shards: empty: expected a folder"
[[ -z $jobs || $jobs =~ ^[0-9]{1,6}%?$ ]] || fail "--jobs: $jobs: expected a number, or a percentage such as 50%"
[[ $sshlogin != *$'\n'* ]] || fail "--sshlogin: holds a newline"
# VALIDATE-ARGS: the flags the script sets itself, or that every shard would act on alike (up to their own `--`,
# after which crankcheck reads every word as a scene).
has_jobs=0
for arg in "${validate_args[@]}"; do
  case $arg in
    --) break ;;
    --out | --out=*) fail "VALIDATE-ARGS: --out: the script gives each shard its own (OUT is the merged report)" ;;
    --shard | --shard=*) fail "VALIDATE-ARGS: --shard: the script gives each shard its own part (N)" ;;
    --profile | --profile=*)
      fail "VALIDATE-ARGS: --profile: every shard would write the one FILE; profile one shard by hand instead" \
        "(crankcheck validate --shard I/N --profile FILE ...)" ;;
    -h | --help) fail "VALIDATE-ARGS: $arg: see crankcheck validate --help" ;;
    --jobs | --jobs=*) has_jobs=1 ;;
  esac
done
command -v parallel >/dev/null || { echo "parallel-shards.sh: GNU parallel not found (Debian: apt-get install parallel)" >&2; exit 3; }

if [[ -z $crankcheck ]]; then
  crankcheck="$(cd "$(dirname "$0")/.." && pwd)/build/bin/crankcheck"
  [[ -x $crankcheck ]] || crankcheck=$(command -v crankcheck) || fail "no crankcheck: build it or give --crankcheck"
fi
[[ -f $crankcheck && -x $crankcheck ]] || fail "--crankcheck: $crankcheck: not an executable program"
# Absolute paths: the same on every host, whatever folder parallel's ssh starts in.
crankcheck=$(realpath -- "$crankcheck") || fail "--crankcheck: $crankcheck: no absolute path"
here=$(pwd -P) || fail "the current folder: no absolute path"
out=$(realpath -m -- "$out") || fail "OUT: $out: no absolute path"
shards=$(realpath -m -- "${shards:-$out.shards}") || fail "--shards: $shards: no absolute path"
[[ $shards != "$out" && $shards/ != "$out"/* && $out/ != "$shards"/* ]] ||
  fail "--shards: \"$shards\": the same folder as OUT \"$out\", or one inside the other"

# OUT, the scenes and the flags are checked by crankcheck's own rules before any shard runs (a folder of the user's
# as OUT once let every shard run, then the merge refused it): `validate --check` runs and creates nothing.
"$crankcheck" validate --check --out "$out" "${validate_args[@]}" >/dev/null || exit $?

# The shards folder holds only what this script and crankcheck put there.
if [[ -e $shards || -L $shards ]]; then
  [[ -d $shards && ! -L $shards ]] || fail "--shards: \"$shards\": exists and is not a folder"
  for entry in "$shards"/* "$shards"/.[!.]*; do
    [[ -e $entry || -L $entry ]] || continue
    name=${entry##*/}
    if [[ $name == parallel-joblog.txt || $name == validate-args ]]; then
      [[ -f $entry && ! -L $entry ]] || fail "--shards: \"$shards\": its \"$name\" is not a file this script wrote"
    else
      [[ $name =~ ^shard-[0-9]+$ || $name =~ ^\.shard-[0-9]+\.crankcheck-partial- ]] ||
        fail "--shards: \"$shards\": holds \"$name\", which this script did not write; choose another folder"
    fi
  done
else
  mkdir -p -- "$shards"
fi

# What each shard runs, as NUL-separated words: N, the working folder, crankcheck, then validate's arguments.
((has_jobs)) || validate_args=(--jobs 1 "${validate_args[@]}")
printf '%s\0' "$n" "$here" "$crankcheck" "${validate_args[@]}" >"$shards/validate-args"
# The one command GNU parallel runs (with -q, the shard's number for {}): fixed text, no user string in it, and no
# brace, so none of parallel's replacement strings. SHARDS reaches it in the environment (--env on other hosts).
worker='i=$1; d=$CRANKCHECK_SHARDS_DIR; set --; while IFS= read -r -d "" a; do set -- "$@" "$a"; done <"$d/validate-args" || exit 3; (($# >= 3)) || exit 3; n=$1 w=$2 c=$3; shift 3; cd -- "$w" || exit 3; exec "$c" validate --shard "$i/$n" --out "$d/shard-$i" "$@"'
export CRANKCHECK_SHARDS_DIR=$shards

parallel_args=(--will-cite --halt never --joblog parallel-joblog.txt --tagstring "shard {}/$n")
[[ -n $jobs ]] && parallel_args+=("--jobs=$jobs")
[[ -n $sshlogin ]] && parallel_args+=("--sshlogin=$sshlogin" --env CRANKCHECK_SHARDS_DIR)
[[ -t 2 ]] && parallel_args+=(--eta)

echo "parallel-shards.sh: $n shards of: crankcheck validate$(printf ' %q' "${validate_args[@]}")" \
  "(folders: $shards/shard-I)" >&2
status=0
# parallel runs in SHARDS, so that its job log's name is a fixed word too.
(cd -- "$shards" && exec parallel "${parallel_args[@]}" -q bash -c "$worker" crankcheck-shard {} \
  ::: $(seq 0 $((n - 1)))) || status=$?

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
done < <(cat -- "$shards/parallel-joblog.txt" 2>/dev/null || true)
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
