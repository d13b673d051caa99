#!/usr/bin/env bash
# install.sh - `make install` (scripts/install.sh, docs/install.md): the release programs
# installed into a temporary prefix answer --version, have a man page each and bash
# completion, and run a tiny campaign from another directory with the installed
# programs only (bin/study runs the bin/shake installed beside it, and nothing of the
# clone is on the PATH); Debian's python3, given the PYTHONPATH line install.sh prints
# for the prefix, imports the installed Python package from there (nothing of the clone
# on its path) and reads the campaign's runs; nothing is written outside the prefix.
. "$(dirname "$0")/lib.sh"
BIN="$REPO/bin"
cd "$TMP" || exit 1
[ -x "$BIN/study" ] || { fail setup "$BIN/study is not built (make all)"; finish; }

P="$TMP/prefix"
(cd "$REPO" && bash scripts/install.sh "$BIN" "$P") >inst.log 2>&1
check install.exit "$(tail -n 3 inst.log)" grep -q "^installed $(make -s --no-print-directory -C "$REPO" print-tools | wc -w) programs" inst.log
tools=$(make -s --no-print-directory -C "$REPO" print-tools)
bad=""
for t in $tools; do
	[ -x "$P/bin/$t" ] || bad="$bad $t:not-installed"
	v=$("$P/bin/$t" --version 2>&1)
	[ $? = 0 ] && grep -q "shakebox [0-9a-f]\{7,\}" <<<"$v" || bad="$bad $t:--version($v)"
	grep -q "^\.SH NAME" "$P/share/man/man1/$t.1" 2>/dev/null &&
		grep -q "^\.TH $(echo "$t" | tr '[:lower:]' '[:upper:]') 1" "$P/share/man/man1/$t.1" || bad="$bad $t:man"
done
[ -z "$bad" ] && ok install.every_program_version_man || fail install.every_program_version_man "$bad"
# the man pages read as man pages (man -l renders them; the help text is in them)
if command -v man >/dev/null; then
	man -l "$P/share/man/man1/study.1" 2>/dev/null | grep -q "study run CAMPAIGN" && ok install.man_renders ||
		fail install.man_renders "$(man -l "$P/share/man/man1/study.1" 2>&1 | head -n 5)"
else
	skip install.man_renders "no man program here (Debian: man-db) to render the pages with"
fi
# completion: study's commands and a command's options, shake's keys
comp=$(bash -c 'source "$1/share/bash-completion/completions/study"
	COMP_WORDS=(study ex); COMP_CWORD=1; _shakebox_study; echo "${COMPREPLY[*]}"
	COMP_WORDS=(study run --retr); COMP_CWORD=2; _shakebox_study; echo "${COMPREPLY[*]}"
	source "$1/share/bash-completion/completions/shake"
	COMP_WORDS=(shake radius_r); COMP_CWORD=1; _shakebox_shake; echo "${COMPREPLY[*]}"' _ "$P" 2>&1)
[ "$comp" = "$(printf 'expand export\n--retries --retry-failed\nradius_ratio=')" ] && ok install.completion ||
	fail install.completion "got: $(tr '\n' '|' <<<"$comp")"

# a tiny campaign by the installed programs only, from another directory: the installed
# shake wrapped to say it ran (the real one moved beside it)
mv "$P/bin/shake" "$P/bin/shake.real"
printf '#!/bin/sh\ntouch "%s/installed_shake_ran"\nexec "%s/bin/shake.real" "$@"\n' "$TMP" "$P" >"$P/bin/shake"
chmod +x "$P/bin/shake"
mkdir -p work && cd work || exit 1
tiny_campaign inst >inst.campaign
touch "$TMP/before"
env -i HOME="$TMP" PATH="$P/bin:/usr/bin:/bin" study run inst.campaign --runs R --jobs 2 --no-progress >run.log 2>&1
rc=$?
check install.campaign_runs "exit $rc: $(tail -n 3 run.log)" eval '[ "$rc" = 0 ] && grep -q "4 done, 0 failed" run.log'
check install.installed_engine_used "no run went through $P/bin/shake" test -e "$TMP/installed_shake_ran"
env -i HOME="$TMP" PATH="$P/bin:/usr/bin:/bin" waiting inst --runs R --no-plot --no-store >w.out 2>w.err
check install.tool_reads "exit $?: $(head -c 300 w.err)" grep -q "^# runs: 4 of the campaign's current grid" w.out
# the Python package, with the PYTHONPATH line install.sh printed for this prefix
pp=$(sed -n 's/^python: .* PYTHONPATH=//p' "$TMP/inst.log")
check install.python_path_printed "no PYTHONPATH line for $P: $(tail -n 2 "$TMP/inst.log")" \
	eval '[ -n "$pp" ] && [ "${pp#"$P"/lib/python}" != "$pp" ] && [ -f "$pp/shakebox/__init__.py" ]'
env -i HOME="$TMP" PATH=/usr/bin:/bin PYTHONPATH="$pp" /usr/bin/python3 -W ignore - R/study.db "$P" >py.out 2>&1 <<'PY'
import sys, shakebox
assert shakebox.__file__.startswith(sys.argv[2] + "/"), "imported from " + shakebox.__file__
rows = shakebox.runs(sys.argv[1], "inst")
for r in rows:
    with shakebox.Run(r["run_file"]) as run:
        assert run.parameters["run_id"] == r["id"] and run.outcome["status"] == r["status"], r["id"]
print("read %d runs" % len(rows))
PY
check install.python_reads "$(tail -n 3 py.out)" grep -qx "read 4 runs" py.out
# nothing written outside the prefix and the working directory (the clone untouched)
out=$(find "$REPO" -newer "$TMP/before" -type f -not -path "$REPO/build/*" -not -path "$REPO/.git/*" 2>/dev/null | head -n 5)
check install.clone_untouched "written in the clone: $out" test -z "$out"
finish
