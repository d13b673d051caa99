#!/usr/bin/env bash
# study_results.sh - results you can trust: every result column of the database equals
# the value in the run file it came from (for a campaign whose intruders rise), the
# table of docs/database.md is `study columns`, a changed campaign file is refused with what
# changed (and kept or forgotten on request), a database rebuilt from the files equals
# the original, export prints the numbers as written, `finished` is when the engine
# wrote the file, and the status ETA comes from what ran.
# tier: slow: campaigns whose every result column is checked against the run files
. "$(dirname "$0")/lib.sh"
study_setup
cd "$TMP" || exit 1

# --- docs/database.md's table is the generated one ---
"$STUDY" columns >cols.md
awk '/<!-- study columns: begin -->/ { on = 1; next } /<!-- study columns: end -->/ { on = 0 } on' \
	"$REPO/docs/database.md" >readme.md
cmp -s cols.md readme.md && ok columns.readme_is_generated ||
	fail columns.readme_is_generated "docs/database.md's table differs from 'study columns': $(diff cols.md readme.md | head -n 3)"

# --- a campaign whose intruders rise (a 2.5x intruder under one row, shaken hard) ---
mk() { # FILE TRAJ_RATE
	cat >"$1" <<EOF
[campaign]
name = rise
seed = 21
replicates = 2
[scene]
$(tiny_scene)
duration = 0.6
traj_rate = $2
snapshots = no
r_min = 0.85
[grid]
frequency = 4, 5
EOF
}
mk c.campaign 100
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 >run1.log 2>&1 || fail run.first "exit $?: $(tail -n 3 run1.log)"
DB=R/study.db
nrisen=$(q $DB "SELECT SUM(risen) FROM runs WHERE campaign = 'rise'")
[ "${nrisen:-0}" -ge 2 ] && ok results.some_risen || fail results.some_risen "only '$nrisen' of 4 intruders rose: the comparison below needs risen runs"

# every stored column, every run: the database holds the file's value (to the bit for reals)
ncmp=0 nbad=0
while IFS='|' read -r _ col _ where _; do
	col=$(echo "$col" | tr -d ' `')
	where=$(echo "$where" | tr -d ' `')
	case "$where" in view:*|"") continue ;; esac
	for id in $(q $DB "SELECT id FROM run WHERE campaign = 'rise' ORDER BY id"); do
		f=R/rise/$id.h5
		case "$where" in
		*'#rows') want=$(dims "$f" "${where%#rows}" | cut -d' ' -f1) ;;
		'(userblock)') want=$(head -c 64 "$f" | sed -n 's/^fnv1a64w //p') ;; # the seal (core/io/h5id.h)
		# not the file's: the seal of the run's rows, by its second definition (lib/rowseal.h)
		'(itsrows)') want=$(/usr/bin/python3 "$REPO/tests/integration/rowseal.py" check $DB | awk -v r="$id" '$1 == r { print $3 }') ;;
		@*) want=$(attr "$f" "/${where#@}") ;;
		*) want=$(attr "$f" "${where%@*}/${where#*@}") ;;
		esac
		got=$(q $DB "SELECT CASE typeof($col) WHEN 'real' THEN printf('%!.17g', $col) ELSE $col END FROM result WHERE campaign = 'rise' AND run = '$id'")
		# h5dump prints reals with %.17g; sqlite's printf needs the ! flag for all 17 digits
		if [ "$got" != "$want" ] && ! awk -v a="$got" -v b="$want" 'BEGIN { exit !(a != "" && b != "" && a + 0 == b + 0) }'; then
			# settle_time of a run from the packing cache is the cache's (the file says 0)
			if [ "$col" = settle_time ] || [ "$col" = settle_steps ]; then
				key=$(q $DB "SELECT cache_key FROM run WHERE campaign = 'rise' AND id = '$id' AND from_cache")
				if [ -n "$key" ]; then
					want=$(attr "R/rise/cache/$key.h5" "/$col")
					awk -v a="$got" -v b="$want" 'BEGIN { exit !(a + 0 == b + 0) }' && { ncmp=$((ncmp + 1)); continue; }
				fi
			fi
			nbad=$((nbad + 1))
			echo "# $id $col: database '$got', file ($where) '$want'"
		fi
		ncmp=$((ncmp + 1))
	done
done < <(tail -n +3 cols.md)
[ "$ncmp" -ge 100 ] && [ "$nbad" = 0 ] && ok results.database_equals_files ||
	fail results.database_equals_files "$nbad of $ncmp values differ (see the # lines)"
# the derived column is its expression
[ "$(q $DB "SELECT COUNT(*) FROM runs WHERE campaign = 'rise' AND intruder_rise_box = intruder_final_y_box - intruder_settled_y_box")" = 4 ] &&
	ok results.rise_is_final_minus_settled || fail results.rise_is_final_minus_settled "intruder_rise_box is not final - settled"
# the drive's Gamma = A (2 pi f)^2 / g and peak velocity 2 pi f A, as columns of the view
[ "$(q $DB "SELECT COUNT(*) FROM runs WHERE campaign = 'rise' AND abs(gamma - amplitude * (2 * 3.141592653589793 * frequency) * (2 * 3.141592653589793 * frequency) / gravity) < 1e-12
	AND abs(v_box - 2 * 3.141592653589793 * frequency * amplitude) < 1e-12 AND gamma > 1.2")" = 4 ] &&
	ok results.gamma_and_v_box || fail results.gamma_and_v_box "$(q $DB "SELECT frequency, amplitude, gamma, v_box FROM runs")"
# one definition of the rise: no second rise-time column, and the engine's waiting time is
# the first box-frame crossing of one diameter in the trajectory (sampled at 100 Hz, so
# within 0.01 s), never the lab-frame one
[ -z "$(q $DB "SELECT name FROM pragma_table_info('runs') WHERE name LIKE '%rise_time%'")" ] &&
	ok results.one_rise_definition || fail results.one_rise_definition "a rise_time column still exists"
nchk=0 nbad=0
for id in $(q $DB "SELECT id FROM runs WHERE campaign = 'rise' AND risen = 1"); do
	f=R/rise/$id.h5
	y0=$(attr "$f" /intruder_settled_y) r=$(attr "$f" /intruder_radius) A=$(h5param "$f" amplitude) fr=$(h5param "$f" frequency)
	wt=$(q $DB "SELECT printf('%.17g', waiting_time) FROM result WHERE campaign = 'rise' AND run = '$id'")
	first=$(h5traj "$f" |
		awk -v y0="$y0" -v r="$r" -v A="$A" -v f="$fr" '{ yb = $3 - A * sin(2 * 3.141592653589793 * f * $1);
			if (yb - y0 > 2 * r) { print $1; exit } }')
	nchk=$((nchk + 1))
	awk -v a="$wt" -v b="$first" 'BEGIN { exit !(b != "" && a <= b + 1e-12 && a > b - 0.0100001) }' ||
		{ nbad=$((nbad + 1)); echo "# $id waiting_time $wt, first box-frame crossing in the trajectory '$first'"; }
done
[ "$nchk" -ge 2 ] && [ "$nbad" = 0 ] && ok results.waiting_time_is_box_frame_crossing ||
	fail results.waiting_time_is_box_frame_crossing "$nbad of $nchk risen runs disagree with their trajectory"

# --- finished is when the engine wrote the file; export prints numbers as written ---
id=$(q $DB "SELECT id FROM run WHERE campaign = 'rise' ORDER BY id LIMIT 1")
[ "$(q $DB "SELECT finished FROM run WHERE campaign = 'rise' AND id = '$id'")" = "$(attr R/rise/$id.h5 /provenance/end_time)" ] &&
	ok results.finished_is_engine_end_time || fail results.finished_is_engine_end_time "run.finished is not the file's end_time"
"$STUDY" export rise --runs "$TMP/R" >e1.csv
head -n 2 e1.csv | awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i } NR == 2 { print $c["r_min"], $c["width"], $c["frequency"] }' >e1.vals
[ "$(cat e1.vals)" = "0.85 20 4" ] || [ "$(cat e1.vals)" = "0.85 20 5" ] && ok export.numbers_as_written ||
	fail export.numbers_as_written "r_min, width, frequency exported as '$(cat e1.vals)'"

# --- options as users type them: --opt=value, and a suggestion for a typo ---
[ "$("$STUDY" export rise --runs="$TMP/R" | md5sum)" = "$("$STUDY" export rise --runs "$TMP/R" | md5sum)" ] &&
	ok options.equals_form || fail options.equals_form "--runs=DIR and --runs DIR differ"
"$STUDY" status --rnus "$TMP/R" >typo.log 2>&1
[ $? = 1 ] && grep -q "did you mean --runs?" typo.log && ok options.suggestion || fail options.suggestion "$(cat typo.log)"

# --- the status ETA is the pace of what ran, not the driver's --jobs ---
cp "$DB" eta.db
q eta.db "UPDATE run SET state = 'pending' WHERE campaign = 'rise' AND id IN (SELECT id FROM run WHERE campaign = 'rise' LIMIT 2);
	UPDATE attempt SET finished = strftime('%Y-%m-%dT%H:%M:%SZ', '2026-01-01 00:00:00', '+' || (10 * (1 + (SELECT COUNT(*) FROM attempt a2 WHERE a2.rowid < attempt.rowid))) || ' seconds');
	UPDATE run SET started = '2026-01-01T00:00:00Z'"
# 4 runs that started together and finished 10, 20, 30, 40 s later: 4 runs in 40 s
e1=$("$STUDY" status rise --db eta.db --jobs 1 | grep ETA)
e2=$("$STUDY" status rise --db eta.db --jobs 64 | grep ETA)
[ "$e1" = "$e2" ] && case "$e1" in *"pace of the last runs (360.0 runs/h)"*) true ;; *) false ;; esac && ok status.eta_from_what_ran ||
	fail status.eta_from_what_ran "ETA depends on --jobs or is not from the pace: '$e1' / '$e2'"

# --- a database rebuilt from the files equals the original ---
"$STUDY" export rise --runs "$TMP/R" >before.csv
mv R/study.db R/study.db.orig
rm -f R/study.db-wal R/study.db-shm
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 >rebuild.log 2>&1 || fail rebuild.run "exit $?: $(tail -n 3 rebuild.log)"
"$STUDY" export rise --runs "$TMP/R" >after.csv
# timing columns aside (started is when a driver saw the run start)
strip() { awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "started") s = i } { $s = ""; print }' OFS=, "$1"; }
if cmp -s <(strip before.csv) <(strip after.csv); then ok rebuild.export_equal; else
	fail rebuild.export_equal "export differs after rebuilding the database: $(diff <(strip before.csv) <(strip after.csv) | head -n 3 | cut -c1-300)"
fi
[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'rise' AND from_cache")" = 4 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM result WHERE campaign = 'rise' AND settle_time > 0")" = 4 ] &&
	ok rebuild.cache_columns || fail rebuild.cache_columns "from_cache/settle_time lost: $(q R/study.db "SELECT from_cache, settle_time FROM runs")"

# --- a database of an older version: its result table is rebuilt from the files ---
q R/study.db "DROP TABLE result; CREATE TABLE result(campaign TEXT, run TEXT, status TEXT, rise_time REAL)"
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 >old.log 2>&1
"$STUDY" export rise --runs "$TMP/R" >old.csv
cmp -s <(strip before.csv) <(strip old.csv) && ok rebuild.old_schema || fail rebuild.old_schema "results not read back: $(diff <(strip before.csv) <(strip old.csv) | head -n 2 | cut -c1-200)"

# --- a changed fixed key: refused, with what changed; nothing runs ---
mk c.campaign 50
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 >chg.log 2>&1
rc=$?
[ "$rc" = 1 ] && grep -q 'traj_rate: 100 -> 50' chg.log && grep -q '4 recorded runs' chg.log &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM run WHERE campaign = 'rise'")" = 4 ] && ok change.refused_with_what_changed ||
	fail change.refused_with_what_changed "exit $rc: $(head -c 400 chg.log)"
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 --keep-old >keep.log 2>&1
[ "$(q R/study.db "SELECT current || ':' || COUNT(*) FROM run WHERE campaign = 'rise' GROUP BY current ORDER BY current" | tr '\n' ' ')" = "0:4 1:4 " ] &&
	ok change.keep_old || fail change.keep_old "$(q R/study.db "SELECT current, state FROM run") $(tail -n 2 keep.log)"
[ "$(q R/study.db "SELECT version FROM campaign WHERE name = 'rise'")" = 2 ] && ok change.version_counted ||
	fail change.version_counted "campaign version $(q R/study.db "SELECT version FROM campaign")"
# back to the first file: its runs are current again, the second file's are now the old ones
mk c.campaign 100
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 --forget-old >forget.log 2>&1
[ "$(q R/study.db "SELECT COUNT(*) || ' ' || SUM(current) FROM run WHERE campaign = 'rise'")" = "4 4" ] &&
	[ "$(ls R/rise/forgotten/*.h5 2>/dev/null | wc -l)" = 4 ] &&
	[ "$(q R/study.db "SELECT COUNT(*) FROM param WHERE campaign = 'rise' AND run NOT IN (SELECT id FROM run)")" = 0 ] &&
	ok change.forget_old || fail change.forget_old "$(q R/study.db "SELECT id, current FROM run") $(ls R/rise/forgotten 2>&1 | head -n 3)"
# an extension (a value added to an axis) is not a change
sed -i 's/^frequency = 4, 5/frequency = 4, 5, 6/' c.campaign
"$STUDY" run c.campaign --runs "$TMP/R" --jobs 2 >ext.log 2>&1 && ok change.extension_allowed ||
	fail change.extension_allowed "exit $?: $(head -c 300 ext.log)"
finish
