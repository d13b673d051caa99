#!/usr/bin/env bash
# preset_evidence.sh - the evidence for each campaign's integrator preset, one place.
#
# docs/preset_evidence.tsv holds one row per measured comparison of `preset = fast`
# against `preset = paper`, written by the benchmark that measured it (make
# bench-accuracy, make validate-lammps), never by hand:
#   KEY <tab> VERDICT <tab> SOURCE <tab> SENTENCE
# VERDICT is one of
#   indistinguishable  the paired comparison found no difference (SENTENCE says the
#                      smallest difference it could have detected);
#   differ             a test at 5 % found a difference;
#   answer_differs     no single test differs, but the claim's own answer (its test within
#                      each preset) is not the same with both presets.
# A campaign file names the rows its preset rests on in a comment line
#   # preset evidence: KEY [KEY ...]
# and the rule is: `preset = fast` only where every row it names is indistinguishable;
# a campaign whose evidence is not (or that names none) runs `paper`. REPRODUCTION.md's
# integrator lines print the rows (scripts/reproduce.sh).
#
#   preset_evidence.sh set KEY VERDICT SOURCE SENTENCE   # add or replace a row (atomic)
#   preset_evidence.sh line CAMPAIGN_FILE                # the evidence in one paragraph
#   preset_evidence.sh check [CAMPAIGN_FILE...]          # "ok ID" / "FAIL ID: why" per file
#                                                        # (default: campaigns/reproduce/*)
# EVIDENCE=FILE reads and writes another table (the tests).
set -u
REPO=$(cd "$(dirname "$0")/.." && pwd)
EVIDENCE=${EVIDENCE:-$REPO/docs/preset_evidence.tsv}
VERDICTS="indistinguishable differ answer_differs"

die() {
	echo "preset_evidence: $*" >&2
	exit 1
}

# the campaign file's keys (its "# preset evidence:" lines) and its preset
keys_of() { sed -n 's/^#[[:space:]]*preset evidence:[[:space:]]*//p' "$1" | tr -s ' \t' '\n\n' | sed '/^$/d'; }
preset_of() {
	awk '/^[[:space:]]*\[/ { sec = $0; gsub(/[[:space:]]/, "", sec); next }
		sec == "[scene]" && /^[[:space:]]*preset[[:space:]]*=/ { v = $0; sub(/^[^=]*=[[:space:]]*/, "", v)
			sub(/[[:space:]]*[#;].*$/, "", v); sub(/[[:space:]]+$/, "", v); print v; exit }' "$1"
}
row_of() { awk -F'\t' -v k="$1" '$1 == k { print; found = 1; exit } END { exit !found }' "$EVIDENCE" 2>/dev/null; }

case ${1:-} in
set)
	[ $# = 5 ] || die "usage: preset_evidence.sh set KEY VERDICT SOURCE SENTENCE"
	k=$2 v=$3 src=$4 s=$5
	case $k in '' | *[!A-Za-z0-9_.-]*) die "KEY: expected [A-Za-z0-9_.-]+, got '$k'" ;; esac
	case " $VERDICTS " in *" $v "*) ;; *) die "VERDICT: expected one of $VERDICTS, got '$v'" ;; esac
	case $src$s in *$'\t'* | *$'\n'*) die "SOURCE and SENTENCE may hold no tab or newline" ;; esac
	tmp=$(mktemp "$EVIDENCE.XXXXXX") || die "cannot write beside $EVIDENCE"
	{
		[ -s "$EVIDENCE" ] && awk -F'\t' -v k="$k" '$1 != k' "$EVIDENCE"
		printf '%s\t%s\t%s\t%s\n' "$k" "$v" "$src" "$s"
	} | LC_ALL=C sort -t$'\t' -k1,1 >"$tmp" && mv "$tmp" "$EVIDENCE" || { rm -f "$tmp"; die "cannot write $EVIDENCE"; }
	;;
line)
	[ $# = 2 ] && [ -f "$2" ] || die "usage: preset_evidence.sh line CAMPAIGN_FILE"
	n=0
	for k in $(keys_of "$2"); do
		if r=$(row_of "$k"); then
			IFS=$'\t' read -r _ v src s <<<"$r"
			printf '%s%s: %s (%s, %s)' "$([ $n = 0 ] || echo '; ')" "$k" "$v" "$s" "$src"
		else
			printf '%s%s: no such row in docs/preset_evidence.tsv' "$([ $n = 0 ] || echo '; ')" "$k"
		fi
		n=$((n + 1))
	done
	[ $n = 0 ] && printf 'none measured'
	echo
	;;
check)
	shift
	[ $# -gt 0 ] || set -- "$REPO"/campaigns/reproduce/*.campaign
	[ -s "$EVIDENCE" ] || die "$EVIDENCE is missing or empty"
	bad=$(awk -F'\t' -v vs=" $VERDICTS " 'NF != 4 || index(vs, " " $2 " ") == 0 { print NR }' "$EVIDENCE" | head -n 1)
	[ -z "$bad" ] || { echo "FAIL evidence.table: $EVIDENCE:$bad: expected KEY, VERDICT ($VERDICTS), SOURCE, SENTENCE"; exit 1; }
	nf=0
	for c in "$@"; do
		id=${c##*/}
		p=$(preset_of "$c")
		why=
		for k in $(keys_of "$c"); do
			if ! r=$(row_of "$k"); then why="$why $k: no such row;"; continue; fi
			IFS=$'\t' read -r _ v _ _ <<<"$r"
			[ "$p" = fast ] && [ "$v" != indistinguishable ] && why="$why $k is $v;"
		done
		[ "$p" = fast ] && [ -z "$(keys_of "$c")" ] && why=" preset fast without a '# preset evidence:' line"
		if [ -n "$why" ]; then
			echo "FAIL evidence.$id: preset ${p:-default}:$why"
			nf=$((nf + 1))
		else
			echo "ok evidence.$id"
		fi
	done
	[ "$nf" = 0 ]
	;;
*) sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'; [ "${1:-}" = --help ] || [ "${1:-}" = -h ] ;;
esac
