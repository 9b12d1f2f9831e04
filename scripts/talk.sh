# Sourced by scripts/run.sh and scripts/test.sh: every step says what it does, and a long
# compile is never silent, piped or not.
#
# `say TEXT`: one line on stderr, with the seconds since the script started.
# `talking CMD...`: runs CMD with its stderr passed through; while CMD's stderr is quiet for
# 20 s (one crate compiling for minutes, which cargo shows on a terminal only as a progress bar
# and in a pipe not at all), says so every 20 s with the last line it printed.

say() {
    printf '[%4ds] %s\n' "$SECONDS" "$*" >&2
}

talking() {
    local log
    log="$(mktemp)"
    (
        quiet=0
        size=0
        while sleep 5; do
            now=$(stat -c %s "$log" 2>/dev/null || echo 0)
            if [ "$now" != "$size" ]; then
                size=$now
                quiet=0
                continue
            fi
            quiet=$((quiet + 5))
            if [ $((quiet % 20)) -eq 0 ]; then
                last="$(tail -n 1 "$log" 2>/dev/null | tr -d '\r' | sed 's/^ *//' | cut -c1-100)"
                say "  still working (${quiet} s since: ${last:-the start})"
            fi
        done
    ) &
    local beat=$!
    local status=0
    "$@" 2> >(tee -a "$log" >&2) || status=$?
    kill "$beat" 2>/dev/null || true
    wait "$beat" 2>/dev/null || true
    rm -f "$log"
    return "$status"
}
