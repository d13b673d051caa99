#!/usr/bin/env bash
# segregation.sh - binary beds and the segregation index (docs/model.md, "Binary beds",
# "Segregation index"). Known answers through the engine: beds of widely spaced grains
# in free fall (no contact, so their order never changes) with the large ones all on
# top read +1 every period, all at the bottom -1, a quarter large in every row 0; the
# summaries are the series' mean and last. size_dist = binary alone draws grains of the
# two default radii in about the default fraction, differs from the uniform bed of the
# same seed, and its index reaches the run file and the campaign's `runs`; the new keys'
# errors name file, line, key and range; a bed of one size asking for the index is
# refused; scripts/segregation.sh prints and plots the series.
# tier: slow: a campaign of binary beds, besides the free-falling beds
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1
G=/observables/segregation

# bed NAME LARGE-ROWS: 6 rows of 5 grains 10 cm apart (r 1, or 2 in the rows named by
# the awk condition LARGE-ROWS on row and col), far above a box of four wall disks
bed() {
	awk -v name="$1" "BEGIN {
		for (row = 0; row < 6; row++) for (col = 0; col < 5; col++)
			printf \"%d %d %d grain 0 0 0\\n\", 5 + 10 * col, 300 + 10 * row, ($2) ? 2 : 1
		print \"0 0 1 wall\"; print \"60 0 1 wall\"; print \"0 400 1 wall\"; print \"60 400 1 wall\" }" >"$1.txt"
	shake_run "$1.log" particles="$1.txt" settle=no amplitude=0 frequency=5 duration=0.6 segregation_samples=2 \
		snapshots=no traj_rate=0 progress=no output="$1.h5" || fail "$1.run" "exit $?: $(tail -n 2 "$1.log")"
}
# every WANT FILE : every period's index of FILE within 1e-12 of WANT (three periods)
every() {
	h5vals "$2" $G/segregation_index/value | awk -v w="$1" '
		{ d = $1 - w; d = d < 0 ? -d : d; m = d > m ? d : m; n++ } END { exit !(n == 3 && m < 1e-12) }'
}
bed top 'row >= 4'
bed bottom 'row < 2'
bed mixed 'col == 2 || (col == 4 && row % 2)'
bed quarter 'col == 1'
every 1 top.h5 && ok free_fall.large_on_top || fail free_fall.large_on_top "$(h5vals top.h5 $G/segregation_index/value | tr '\n' ' ')"
every -1 bottom.h5 && ok free_fall.large_at_bottom ||
	fail free_fall.large_at_bottom "$(h5vals bottom.h5 $G/segregation_index/value | tr '\n' ' ')"
every 0 quarter.h5 && ok free_fall.mixed || fail free_fall.mixed "$(h5vals quarter.h5 $G/segregation_index/value | tr '\n' ' ')"
# a bed neither mixed nor segregated: one large grain more in the odd rows. Large: col 2
# of every row and col 4 of rows 1, 3, 5: 9 grains, their rows summing to 24; small: the
# other 21, rows summing to 75 - 24; all on top, the 9 highest would be row 5 and four of
# row 4 (41), the rest 34; heights are 10 cm a row, which cancels
want=$(awk 'BEGIN { printf "%.17g", (24 / 9 - 51 / 21) / (41 / 9 - 34 / 21) }')
every "$want" mixed.h5 && ok free_fall.in_between || fail free_fall.in_between "$(h5vals mixed.h5 $G/segregation_index/value | tr '\n' ' '), want $want"
awk -v a="$(attr top.h5 /segregation_index_final)" -v b="$(attr bottom.h5 /segregation_index_final)" \
	'BEGIN { exit !(a != "" && b != "" && 1 - a < 1e-12 && b + 1 < 1e-12) }' && ok summary.final || fail summary.final "final $(attr top.h5 /segregation_index_final), $(attr bottom.h5 /segregation_index_final)"
# the mean is the periods' mean, the final the last period's (two samples each, averaged)
awk -v a="$(attr mixed.h5 /segregation_index_mean)" -v w="$want" 'BEGIN { d = a - w; exit !(a != "" && d < 1e-12 && d > -1e-12) }' &&
	[ "$(attr mixed.h5 /segregation_index_final)" = "$(h5vals mixed.h5 $G/segregation_index/value | tail -n 1)" ] &&
	[ "$(attr mixed.h5 $G/samples_per_period)" = 2 ] && ok summary.mean ||
	fail summary.mean "mean $(attr mixed.h5 /segregation_index_mean), want $want"

# scripts/segregation.sh: the series as TSV (three periods each), a figure, and a file
# without the series refused
"$REPO/scripts/segregation.sh" --png fig.png top.h5 bottom.h5 >tool.tsv 2>tool.err &&
	[ "$(grep -c "top.h5" tool.tsv)" = 3 ] && [ "$(awk -F'\t' '$1 ~ /bottom.h5$/ { print $3 + 0 }' tool.tsv | sort -u)" = -1 ] &&
	[ "$(head -c 4 fig.png | tail -c 3)" = PNG ] && ok tool.plot || fail tool.plot "$(head -c 300 tool.err) $(head -n 3 tool.tsv)"
shake_run none.log particles=top.txt settle=no amplitude=0 duration=0.2 snapshots=no traj_rate=0 output=none.h5
"$REPO/scripts/segregation.sh" none.h5 >/dev/null 2>none.err
[ $? = 1 ] && contains none.err "segregation_samples" && ok tool.without_series || fail tool.without_series "$(cat none.err)"

# size_dist = binary alone: radii 1 and 2 only (0.7 s at 3.2 Hz: two periods), about a fifth large (60 grains: 12 expected,
# 4 to 22 is beyond 3 standard deviations), the uniform bed's run differs
tiny_bed radius_ratio=0 duration=0.7 segregation_samples=1 snapshots=yes traj_rate=0 progress=no
shake_run b.log "${BEDARGS[@]}" size_dist=binary output=b.h5 || fail binary.run "exit $?: $(tail -n 3 b.log)"
h5vals b.h5 /particles/bed/radius | sort -g | uniq -c | awk '
	{ n[$2] = $1; k++ } END { exit !(k == 2 && (1 in n) && (2 in n) && n[2] >= 4 && n[2] <= 22 && n[1] + n[2] == 60) }' &&
	ok binary.radii || fail binary.radii "radii $(h5vals b.h5 /particles/bed/radius | sort -g | uniq -c | tr '\n' ' ')"
s=$(h5vals b.h5 $G/segregation_index/value | wc -l)
awk -v m="$(attr b.h5 /segregation_index_mean)" -v f="$(attr b.h5 /segregation_index_final)" -v n="$s" \
	'BEGIN { exit !(m != "" && f != "" && m >= -1 && m <= 1 && f >= -1 && f <= 1 && n == 2) }' && ok binary.index ||
	fail binary.index "mean '$(attr b.h5 /segregation_index_mean)', final '$(attr b.h5 /segregation_index_final)', $s periods"
shake_run u.log "${BEDARGS[@]}" output=u.h5 || fail uniform.run "exit $?: $(tail -n 3 u.log)"
[ "$(h5vals u.h5 /particles/bed/radius | sort -u | wc -l)" -gt 2 ] && ok binary.differs_from_uniform ||
	fail binary.differs_from_uniform "the uniform bed has $(h5vals u.h5 /particles/bed/radius | sort -u | wc -l) radii"
# an explicit size_dist = uniform is the default's run, bit for bit
shake_run x.log "${BEDARGS[@]}" size_dist=uniform output=x.h5 &&
	same_output u.h5 x.h5 output size_dist && ok uniform.default_bits || fail uniform.default_bits "size_dist = uniform differs from the default"

# errors: file, line, key, range; the other size law's keys refused; one size refused.
# refused ID TEXT WORD... : a scene file of TEXT is refused (exit 1) with every WORD said
refused() {
	local id=$1 text=$2 w
	shift 2
	printf '%b' "$text" >"$id.ini"
	shake_run "$id.log" "$id.ini" output=none
	[ $? = 1 ] || { fail "errors.$id" "not refused: $(head -c 300 "$id.log")"; return; }
	for w in "$@"; do contains "$id.log" "$w" || { fail "errors.$id" "no '$w' in: $(head -c 300 "$id.log")"; return; }; done
	ok "errors.$id"
}
refused large_fraction_range 'n_grains = 60\nsize_dist = binary\nlarge_fraction = 1.5\n' large_fraction_range.ini:3: \
	large_fraction "[0, 1]"
refused radii_order 'size_dist = binary\nr_small = 1.5\nr_large = 1.2\n' radii_order.ini:2: r_small r_large
refused size_dist_word 'size_dist = bimodal\n' size_dist_word.ini:1: uniform binary
refused other_law_keys 'size_dist = binary\nr_max = 1.3\n' other_law_keys.ini:2: r_max "size_dist = uniform"
# ... but at its default it may be given (the study driver passes every key)
shake_run def.log size_dist=binary r_min=0.85 r_max=1.15 n_grains=0 radius_ratio=1 duration=0 output=none &&
	ok errors.other_law_default_allowed || fail errors.other_law_default_allowed "$(head -c 300 def.log)"
awk '/grain/ { $3 = 1 } 1' top.txt >one.txt
shake_run one.log particles=one.txt settle=no amplitude=0 duration=0.2 segregation_samples=1 snapshots=no traj_rate=0 output=one.h5
[ $? = 1 ] && contains one.log "segregation_samples" && contains one.log "all of radius 1" &&
	ok errors.one_size || fail errors.one_size "$(head -c 300 one.log)"

# a campaign of binary beds: the index in its runs (the view), equal to the run files'
# (0.6 s: three periods at 5 Hz, two at 4 Hz; no intruder)
tiny_campaign seg 5 'size_dist = binary' 'radius_ratio = 0' 'segregation_samples = 1' >seg.campaign
sed -i 's/^radius_ratio = 2$//; s/^duration = 0.2$/duration = 0.6/' seg.campaign
"$STUDY" run seg.campaign --runs "$TMP/R" --jobs 2 --no-progress >study.log 2>&1 || fail campaign.run "exit $?: $(tail -n 3 study.log)"
rows=$(q R/study.db "SELECT id, segregation_index_mean, segregation_index_final FROM runs WHERE campaign = 'seg'")
n=0 good=0
while IFS='|' read -r id m f; do
	n=$((n + 1))
	h=$(ls R/seg/"$id"*.h5 2>/dev/null | head -n 1)
	[ -n "$m" ] && [ -n "$f" ] && [ -n "$h" ] &&
		awk -v a="$m" -v b="$(attr "$h" /segregation_index_mean)" -v c="$f" -v d="$(attr "$h" /segregation_index_final)" \
			'function near(x, y) { return (x - y) ^ 2 <= 1e-24 * (y ^ 2 + 1e-300) }
			BEGIN { exit !(b != "" && d != "" && near(a, b) && near(c, d)) }' && good=$((good + 1))
done <<<"$rows"
[ "$n" = 4 ] && [ "$good" = 4 ] && ok campaign.runs_columns || fail campaign.runs_columns "$good of $n runs agree: $rows"
finish
