#!/usr/bin/env bash
# study_view.sh - study view and the run files in study export: the view is a tree of links
# named by the parameters that vary (frequency=F/seed=S.h5), each to the run's own file
# (the same bytes as the export's `file` column); a run without a file is left out and
# counted; a second view replaces the first; a path that this command did not make is
# refused and left as it was; a value with '/' makes no other path. study export: a
# `file` column with each run's absolute path, and --units a row of units read from the
# engine's and the result tables (frequency Hz, waiting_time s, gamma none).
. "$(dirname "$0")/lib.sh"
cd "$TMP" || exit 1
study_setup
tiny_campaign view >view.campaign
fixture_runs view.campaign runs >/dev/null || { fail setup "the campaign did not run: $(tail -n 3 runs.log)"; finish; }

"$STUDY" view view.campaign v --runs runs >v.out 2>v.err && ok view.made || fail view.made "exit $?: $(cat v.err)"
check view.says "no summary: $(cat v.out)" grep -q "4 links to the run files of 'view' by frequency, seed" v.out
n=$(find v -type l | wc -l)
[ "$n" = 4 ] && ok view.four_links || fail view.four_links "$n links: $(find v | head)"
# each link: frequency=F/seed=S.h5 to the file the export names for that run
"$STUDY" export view.campaign --runs runs >e.csv 2>e.err || fail export "$(cat e.err)"
bad=$(/usr/bin/python3 - <<'PY'
import csv, os
rows = list(csv.DictReader(open("e.csv")))
bad = []
for r in rows:
    f = float(r["frequency"])
    link = "v/frequency=%s/seed=%s.h5" % (("%g" % f), r["seed"])
    if not os.path.islink(link):
        bad.append("no " + link)
    elif os.readlink(link) != r["file"] or not os.path.isabs(r["file"]):
        bad.append("%s -> %s, export %s" % (link, os.readlink(link), r["file"]))
    elif not os.path.samefile(link, "runs/view/%s.h5" % r["id"]):
        bad.append(link + " is not run " + r["id"])
print("; ".join(bad))
PY
)
[ -z "$bad" ] && ok view.links_are_the_runs || fail view.links_are_the_runs "$bad"
head -n 1 e.csv | grep -q ',file$' && ok export.file_last || fail export.file_last "$(head -n 1 e.csv | tail -c 80)"

# --units: the row under the header, from the tables
"$STUDY" export view.campaign --runs runs --units >u.csv 2>u.err || fail export_units "$(cat u.err)"
got=$(/usr/bin/python3 -c '
import csv, sys
r = list(csv.reader(open("u.csv")))
print(" ".join("%s=%s" % (c, r[1][r[0].index(c)]) for c in sys.argv[1:]), len(r))' frequency waiting_time gamma state v_box)
want="frequency=Hz waiting_time=s gamma= state= v_box=$("$SHAKE" --params | awk -F'\t' '$1 == "amplitude" { print $3 }')/s 6"
[ "$got" = "$want" ] && ok export.units_row || fail export.units_row "$got, not $want"

# a run without its file: left out, counted; the view made again replaces the first
id=$(sed -n 2p e.csv | awk -F, -v c="$(head -n 1 e.csv | tr ',' '\n' | grep -nx id | cut -d: -f1)" '{ print $c }')
mv "runs/view/$id.h5" aside.h5
"$STUDY" view view.campaign v --runs runs >v2.out 2>v2.err
[ "$(find v -type l | wc -l)" = 3 ] && grep -q "1 runs without a file yet" v2.out && ok view.remade_without_missing ||
	fail view.remade_without_missing "$(cat v2.out v2.err) $(find v -type l | wc -l)"
mv aside.h5 "runs/view/$id.h5"
ls -d v.tmp.* v.old.* >/dev/null 2>&1 && fail view.no_litter "$(ls -d v.*)" || ok view.no_litter

# refused: a directory study view did not make, a file, a symbolic link; each left as it was
mkdir mine && echo keep >mine/notes.txt
"$STUDY" view view.campaign mine --runs runs >r.out 2>r.err
rc=$?
[ "$rc" = 1 ] && grep -q "mine: a directory stands there that study view did not make" r.err && [ "$(cat mine/notes.txt)" = keep ] &&
	[ "$(ls -A mine)" = notes.txt ] && ok refuse.foreign_dir || fail refuse.foreign_dir "exit $rc: $(cat r.err)"
ln -s mine lnk
"$STUDY" view view.campaign lnk --runs runs >r.out 2>r.err
rc=$?
[ "$rc" = 1 ] && grep -q "lnk: a symbolic link stands there" r.err && [ -L lnk ] && ok refuse.symlink ||
	fail refuse.symlink "exit $rc: $(cat r.err)"
# another campaign's view is not this one's to remake
"$STUDY" view other v --runs runs >r.out 2>r.err
rc=$?
[ "$rc" = 1 ] && [ "$(find v -type l | wc -l)" = 3 ] && ok refuse.unknown_campaign || fail refuse.unknown_campaign "exit $rc: $(cat r.err)"
"$STUDY" view view.campaign --runs runs >r.out 2>r.err
[ $? = 1 ] && ok refuse.no_dir || fail refuse.no_dir "$(cat r.err)"
finish
