# strip_how.sh - sourced by the scripts that compare a study export with an
# uninterrupted campaign's (tests/integration/faults.sh, tests/stress/campaign_faults.sh):
# strip_how FILE prints the export without the columns that say when, where, how often
# and how a run was made, not what it gave (docs/testing.md, "Equals"): attempts,
# from_cache (a run that settled its bed itself after the packing cache was lost: the
# same bits, docs/database.md), started, finished, wall_seconds, host, git_hash, git_dirty,
# file (the run file's absolute path: where the runs directory is).
strip_how() {
	awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^(attempts|from_cache|started|finished|wall_seconds|host|git_hash|git_dirty|file)$/) drop[i] = 1 }
		{ s = ""; for (i = 1; i <= NF; i++) if (!drop[i]) s = s $i ","; print s }' "$1"
}
