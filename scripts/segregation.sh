#!/usr/bin/env bash
# segregation.sh - the grains' segregation index against time, of one or more run files
# recorded with segregation_samples > 0 (/observables/segregation; the index:
# docs/model.md, "Segregation index": +1 large grains all above the small, -1 all below).
#
#   scripts/segregation.sh [--png FILE | --pdf FILE] RUN.h5...
#
# Prints the series as TSV (file, time in s, index, frequency in Hz), one row per drive
# period, and with --png or --pdf draws it with gnuplot (one line per run file, the
# index's range -1 .. 1 and 0 marked). Exit 1 on a file without the series.
set -euo pipefail
usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; }
fig='' term=''
while [ $# -gt 0 ]; do
	case $1 in
	-h | --help) usage; exit 0 ;;
	--png | --pdf)
		[ $# -ge 2 ] || { echo "segregation.sh: $1 needs a file name" >&2; exit 1; }
		term=${1#--} fig=$2
		shift 2
		;;
	--) shift; break ;;
	-*) echo "segregation.sh: unknown option '$1' (see --help)" >&2; exit 1 ;;
	*) break ;;
	esac
done
[ $# -ge 1 ] || { usage >&2; exit 1; }
g=/observables/segregation
# a dataset's values, one per line (the first DATA block: the dataset's, not its attributes')
col() { h5dump -m %.17g -d "$2" -y -w 0 "$1" | awk '/DATA \{/ && !done { on = 1; next } on && /\}/ { on = 0; done = 1 }
	on { gsub(/,/, " "); for (i = 1; i <= NF; i++) print $i }'; }
tsv=$(mktemp)
trap 'rm -f "$tsv"' EXIT
for f in "$@"; do
	h5dump -H -d $g/segregation_index/value "$f" >/dev/null 2>&1 ||
		{ echo "segregation.sh: $f: no $g (a run with segregation_samples > 0)" >&2; exit 1; }
	paste <(col "$f" $g/segregation_index/time) <(col "$f" $g/segregation_index/value) \
		<(col "$f" $g/frequency/value) | awk -v f="$f" -v OFS='\t' '{ print f, $1, $2, $3 }' >>"$tsv"
done
echo -e "# file\ttime_s\tsegregation_index\tfrequency_Hz"
cat "$tsv"
[ -n "$fig" ] || exit 0
command -v gnuplot >/dev/null || { echo "segregation.sh: --$term needs gnuplot" >&2; exit 1; }
{
	if [ "$term" = png ]; then echo "set terminal pngcairo size 800,450"; else echo "set terminal pdfcairo size 6in,3.4in"; fi
	echo "set output '$fig'"
	echo "set xlabel 'time (s)'; set ylabel 'segregation index S'; set yrange [-1.05:1.05]"
	echo "set arrow from graph 0, first 0 to graph 1, first 0 nohead dt 2 lc rgb 'gray'"
	echo "set key bottom right noenhanced"
	printf "plot "
	n=0
	for f in "$@"; do
		[ $n -gt 0 ] && printf ", \\\\\n  "
		printf "'%s' using 2:(strcol(1) eq '%s' ? \$3 : 1/0) with linespoints pt 7 ps 0.4 title '%s'" "$tsv" "$f" "${f##*/}"
		n=$((n + 1))
	done
	echo
} | gnuplot
[ -s "$fig" ] || { echo "segregation.sh: gnuplot wrote no $fig" >&2; exit 1; }
