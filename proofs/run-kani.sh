#!/usr/bin/env bash
# Run the Kani harnesses of proofs/ one by one, each with a timeout, and
# record the results in proofs/KANI_RESULTS.md (and the machine-readable
# proofs/kani-results.tsv it is built from).
#
# Usage: proofs/run-kani.sh [-t SECONDS] [-j JOBS] [-s SOLVER] [HARNESS ...]
#   -t  per-harness timeout (default 600)
#   -j  harnesses verified at once (default 1)
#   NICE (environment) niceness of each run (default 15)
#   -m  run nothing: only merge the results of interrupted runs and rewrite
#       the table
#   -s  CBMC solver passed to `cargo kani --solver` (default: Kani's own,
#       CaDiCaL; see "solver" below)
#   HARNESS  names of #[kani::proof] functions (default: every one in proofs/
#            except the retired ones)
#
# Retired harnesses: proofs/kani-retired.tsv lists, per line, a harness and
# (after a tab) why Kani cannot decide it and which engine covers its
# property instead. They are not run by default (name one to run it), and
# their rows say RETIRED with the time and versions of their last attempt.
#
# Running a subset updates only those rows of the table; the other rows keep
# their previous result, version and commit.
#
# Kani is not vendored: install it (https://model-checking.github.io/kani/)
# so that `cargo kani` and `cbmc` are on PATH. Without it this script says so
# and changes nothing.
#
# Solver: Kani asks CBMC for CaDiCaL. A CBMC built without it (e.g. Debian's
# package) warns "The specified solver, 'cadical', is not available" and
# falls back to MiniSat; then pass `-s kissat` (or `-s cadical` with an
# external binary: `-s bin=cadical`) to get a modern solver.
set -u
cd "$(dirname "$0")/.."

timeout_s=600
jobs=1
solver=""
merge_only=0
while getopts "t:j:s:mh" opt; do
    case "$opt" in
    t) timeout_s="$OPTARG" ;;
    j) jobs="$OPTARG" ;;
    s) solver="$OPTARG" ;;
    m) merge_only=1 ;;
    *)
        sed -n '2,24p' "$0"
        exit 2
        ;;
    esac
done
shift $((OPTIND - 1))

if ! command -v cargo-kani >/dev/null 2>&1 || ! cargo kani --version >/dev/null 2>&1; then
    echo "Kani is not installed (no working 'cargo kani' on PATH): nothing was run," >&2
    echo "proofs/KANI_RESULTS.md is unchanged. See https://model-checking.github.io/kani/install-guide.html" >&2
    exit 3
fi
if ! command -v cbmc >/dev/null 2>&1; then
    echo "CBMC is not on PATH (Kani needs cbmc, goto-cc, goto-instrument, symtab2gb): nothing was run." >&2
    exit 3
fi

kani_version=$(cargo kani --version 2>/dev/null | head -1 | sed 's/^cargo-kani //')
cbmc_version=$(cbmc --version 2>/dev/null | head -1 | sed 's/ .*//')
commit=$(git rev-parse --short=10 HEAD 2>/dev/null || echo unknown)
if ! git diff --quiet HEAD -- src Cargo.toml 'proofs/*.rs' 2>/dev/null; then
    commit="$commit+uncommitted"
fi
solver_label=${solver:-default}

# Every harness: "file<TAB>name", in file order.
list_harnesses() {
    for f in proofs/*.rs; do
        awk -v f="$f" '
            /^[[:space:]]*(pub(\(crate\))? )?mod [a-z_0-9]+ \{/ { match($0, /mod [a-z_0-9]+/); m = substr($0, RSTART + 4, RLENGTH - 4) }
            /#\[kani::proof\]/ { want = 1; next }
            want && /fn kani_[A-Za-z0-9_]*\(/ {
                match($0, /fn kani_[A-Za-z0-9_]*/)
                print f "\t" substr($0, RSTART + 3, RLENGTH - 3) "\t" m
                want = 0
            }' "$f"
    done
}

# The property of a harness: the first line of its doc comment, if any,
# else the name of the first property function its body calls.
property_of() {
    local file=$1 name=$2
    awk -v n="$name" '
        /^[[:space:]]*\/\/\/ / { sub(/^[[:space:]]*\/\/\/ /, ""); if (doc == "") doc = $0; next }
        /#\[kani::/ { next }
        $0 ~ "fn " n "\\(" { found = 1; if (doc != "") { print doc; exit } ; next }
        found && /assert!\(/ {
            match($0, /assert!\([a-z_0-9]+/); print substr($0, RSTART + 8, RLENGTH - 8); exit
        }
        { if (!found) doc = "" }
    ' "$file" | sed 's/|/\\|/g'
}

backend_of() {
    case "$1" in
    *_i16f16 | *_i16f16_*) echo I16F16 ;;
    *_f32 | *_f32_*) echo f32 ;;
    *_f64) echo f64 ;;
    *_q15) echo Q15 ;;
    *) echo integer ;;
    esac
}

tsv=proofs/kani-results.tsv
retired=proofs/kani-retired.tsv
md=proofs/KANI_RESULTS.md
logdir=${CARGO_TARGET_DIR:-target}/kani-logs
mkdir -p "$logdir"
[ -f "$tsv" ] || printf 'harness\tfile\tproperty\tbackend\tresult\ttime_s\tkani\tcbmc\tsolver\tcommit\n' >"$tsv"

all=$(list_harnesses)
if [ $# -gt 0 ]; then
    sel=""
    for h in "$@"; do
        line=$(printf '%s\n' "$all" | awk -F'\t' -v h="$h" '$2 == h')
        if [ -z "$line" ]; then
            echo "no #[kani::proof] harness named $h in proofs/" >&2
            exit 2
        fi
        sel="$sel$line"$'\n'
    done
else
    sel=$(printf '%s\n' "$all" | awk -F'\t' 'NR == FNR { r[$1] = 1; next } !($2 in r)' \
        <(grep -v '^#' "$retired" 2>/dev/null) -)$'\n'
fi

echo "kani $kani_version, cbmc $cbmc_version, commit $commit, timeout ${timeout_s}s, solver $solver_label"

run_one() {
    local file=$1 name=$2 module=$3
    local stem=${file##*/}
    local path="proofs::${stem%.rs}::$module::$name"
    local log="$logdir/$name.log"
    local solver_args=()
    [ -n "$solver" ] && solver_args=(--solver "$solver")
    local start end secs result
    start=$(date +%s.%N)
    timeout --kill-after=30 $((timeout_s + 600)) \
        nice -n "${NICE:-15}" cargo kani --harness "$path" --exact -Z unstable-options -Z stubbing \
        --harness-timeout "${timeout_s}s" --output-format terse "${solver_args[@]}" \
        >"$log" 2>&1
    local rc=$?
    end=$(date +%s.%N)
    secs=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.0f", b - a }')
    # Kani's own verification time, when it reports one.
    local vt
    vt=$(grep -o 'Verification Time: [0-9.]*s' "$log" | tail -1 | grep -o '[0-9.]*')
    if grep -q 'VERIFICATION:- SUCCESSFUL' "$log"; then
        result=VERIFIED
    elif grep -qi 'timed out\|harness-timeout\|TIMEOUT' "$log" || [ $rc -eq 124 ] || [ $rc -eq 137 ] || [ $rc -eq 143 ]; then
        result=TIMEOUT
    elif grep -q 'run out of memory' "$log"; then
        # CBMC's exit, not a failed check.
        result="OUT OF MEMORY"
    elif grep -q 'VERIFICATION:- FAILED' "$log"; then
        result=FAILED
    else
        result="ERROR(rc=$rc)"
    fi
    [ -n "$vt" ] && secs=$(awk -v v="$vt" 'BEGIN { printf "%.1f", v }')
    local prop backend
    prop=$(property_of "$file" "$name")
    backend=$(backend_of "$name")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$file" "$prop" "$backend" \
        "$result" "$secs" "$kani_version" "$cbmc_version" "$solver_label" "$commit" >"$logdir/$name.row"
    echo "$name: $result (${secs}s) log: $log"
}

export -f run_one property_of backend_of
export timeout_s solver solver_label kani_version cbmc_version commit logdir

if [ "$merge_only" = 0 ]; then
    printf '%s' "$sel" | awk 'NF' | xargs -P "$jobs" -L 1 bash -c 'run_one "$0" "$1" "$2"'
fi

# Merge the new rows into the table (by harness name), keep the rest. Rows
# left by an interrupted earlier run are merged too.
tmp=$(mktemp)
cp "$tsv" "$tmp"
while IFS=$'\t' read -r file name _module; do
    [ -z "$name" ] && continue
    row="$logdir/$name.row"
    [ -f "$row" ] || continue
    awk -F'\t' -v n="$name" '$1 != n' "$tmp" >"$tmp.2" && mv "$tmp.2" "$tmp"
    cat "$row" >>"$tmp"
    rm -f "$row"
done <<<"$all"
# Harnesses never run yet get a NOT RUN row; rows of removed harnesses go.
while IFS=$'\t' read -r file name _module; do
    [ -z "$name" ] && continue
    if ! awk -F'\t' -v n="$name" '$1 == n { f = 1 } END { exit !f }' "$tmp"; then
        printf '%s\t%s\t%s\t%s\tNOT RUN\t-\t-\t-\t-\t-\n' "$name" "$file" \
            "$(property_of "$file" "$name")" "$(backend_of "$name")" >>"$tmp"
    fi
done <<<"$all"
# Retired harnesses: result RETIRED, the rest of the row from their last
# attempt.
if [ -f "$retired" ]; then
    awk -F'\t' -v OFS='\t' 'NR == FNR { if ($0 !~ /^#/) r[$1] = 1; next }
        FNR > 1 && ($1 in r) && $5 != "VERIFIED" { $5 = "RETIRED" } { print }' "$retired" "$tmp" >"$tmp.2" &&
        mv "$tmp.2" "$tmp"
fi
{
    head -1 "$tmp"
    tail -n +2 "$tmp" | awk -F'\t' -v all="$(printf '%s\n' "$all" | cut -f2 | tr '\n' ' ')" '
        BEGIN { n = split(all, a, " "); for (i = 1; i <= n; i++) ord[a[i]] = i }
        ($1 in ord) { print ord[$1] "\t" $0 }' | sort -n | cut -f2-
} >"$tsv"
rm -f "$tmp"

# The Markdown table.
{
    echo "# Kani results"
    echo
    echo "Produced by \`proofs/run-kani.sh\` (one \`cargo kani --harness NAME --exact\` per harness,"
    echo "with \`--harness-timeout\`); do not edit by hand. Time is Kani's verification time"
    echo "(wall-clock seconds when Kani does not report one), on a shared 2-core machine"
    echo "under \`nice\`. \`commit\` is the commit the harness was run on."
    echo
    awk -F'\t' '
        { c[$5]++ }
        END {
            printf "Summary: %d harnesses", NR - 1
            for (k in c) if (k != "result") printf ", %s %d", k, c[k]
            print "."
        }' "$tsv"
    echo
    echo "| harness | file | property | backend | result | time (s) | Kani | CBMC | solver | commit |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    tail -n +2 "$tsv" | awk -F'\t' '{ printf "| `%s` | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10 }'
    if [ -f "$retired" ]; then
        echo
        echo "## Retired harnesses"
        echo
        echo "Kani cannot decide these (the reason, and the engine that covers the property instead):"
        echo
        grep -v '^#' "$retired" | awk -F'\t' 'NF >= 2 { printf "- `%s`: %s\n", $1, $2 }'
    fi
    if [ -f proofs/KANI_NOTES.md ]; then
        echo
        cat proofs/KANI_NOTES.md
    fi
} >"$md"
echo "wrote $md"
