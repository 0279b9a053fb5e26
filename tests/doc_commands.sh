#!/bin/bash
# make check-doc-commands: the animation commands of docs/animations.md and of the README's
# workflow step 4 (Animate), run as written from the repository's folder over their first 8 frames:
# the GNU parallel lines (not the --sshlogin ones, which need other hosts) and the
# ./raytracer lines given scene files. Each runs with `-o frames` pointed at a temporary
# folder and `--frames 0:7` added (and `--samples 1` when it names assignment 3's scenes); it
# must exit 0 and write 8 frames. Exit status 0 when every command did, 1 otherwise (also
# when the pages have no such command, or without ../shared, whose scenes the commands name).
set -u
cd "$(dirname "$0")/.." || exit 1
FRAMES=8
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT

if [ ! -d ../shared/scenes/hw2 ]; then
    echo "check-doc-commands: FAIL: ../shared/scenes/hw2 not found (the commands render its scenes)"
    exit 1
fi
if [ ! -x ./raytracer ]; then
    echo "check-doc-commands: FAIL: ./raytracer not built"
    exit 1
fi

# The commands of interest among a Markdown text's indented code lines.
commands() {
    grep -E '^    (parallel |\./raytracer )' | grep -v -e '--sshlogin' | grep -F '.json' | sed 's/^    //'
}
readme_animations() { awk '/^\*\*[0-9]+\. /{on = ($0 ~ /^\*\*4\. Animate/)} /^## /{on = 0} on' README.md; }

failed=0
n=0
run() {  # run SOURCE COMMAND
    local source=$1 cmd=$2 out
    n=$((n + 1))
    out="$tmp/frames_$n"
    if [[ $cmd != *" -o frames "* ]]; then
        echo "FAIL ($source): no '-o frames', so not checked: $cmd"
        failed=1
        return
    fi
    local run_cmd=${cmd/ -o frames / -o $out } extra="--frames 0:$((FRAMES - 1))"
    # Assignment 3's frames take many samples per pixel (tap_water: 64 at 1000x1000): one here.
    [[ $cmd == *scenes/hw3/* ]] && extra+=" --samples 1"
    run_cmd=${run_cmd/.\/raytracer /./raytracer $extra }
    [[ $run_cmd == parallel\ * ]] && run_cmd="parallel --will-cite ${run_cmd#parallel }"
    bash -c "$run_cmd" >"$tmp/log_$n" 2>&1
    local rc=$? written
    written=$(find "$out" -name '*.png' 2>/dev/null | wc -l)
    if [ "$rc" -eq 0 ] && [ "$written" -eq "$FRAMES" ]; then
        echo "ok ($source): $cmd"
    else
        echo "FAIL ($source): exit $rc, $written of $FRAMES frames written: $cmd"
        echo "  as run: $run_cmd"
        sed 's/^/  | /' "$tmp/log_$n" | head -20
        failed=1
    fi
}

parallel_lines=0
while IFS= read -r cmd; do
    [[ $cmd == parallel\ * ]] && parallel_lines=$((parallel_lines + 1))
    run docs/animations.md "$cmd"
done < <(commands < docs/animations.md)
while IFS= read -r cmd; do
    run "README.md, step 4" "$cmd"
done < <(readme_animations | commands)

if [ "$parallel_lines" -eq 0 ]; then
    echo "FAIL: docs/animations.md has no GNU parallel line to run (did its format change?)"
    failed=1
fi
if [ "$failed" -ne 0 ]; then
    echo "check-doc-commands: FAIL"
    exit 1
fi
echo "check-doc-commands: $n commands ran as written, $FRAMES frames each"
