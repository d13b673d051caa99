# lib.sh - helpers of the stress tests (sourced): read HDF5 datasets of a run as
# columns and summarise its final state. Needs h5dump (hdf5-tools).

# h5col FILE DATASET : the dataset's numbers, one per line (row-major), %.17g
h5col() {
	local t
	t=$(mktemp "${TMPDIR:-/tmp}/h5col.XXXXXX")
	if h5dump -d "$2" -m %.17g -y -o "$t" --ddl=/dev/null "$1" >/dev/null 2>&1; then
		tr -s ', \n' '\n' <"$t" | awk 'NF'
	fi
	rm -f "$t"
}

# final_stats FILE : "n_mobile ke_per_disk mean_y max_speed" of the mobile disks in
# /final (translational + rotational kinetic energy, I = m R^2 / 2; erg, cm, cm/s)
final_stats() {
	local f=$1 d
	d=$(mktemp -d "${TMPDIR:-/tmp}/fstat.XXXXXX")
	h5col "$f" /final/species >"$d/k"
	h5col "$f" /final/mass >"$d/m"
	h5col "$f" /final/radius >"$d/r"
	h5col "$f" /final/y >"$d/y"
	h5col "$f" /final/vx >"$d/vx"
	h5col "$f" /final/vy >"$d/vy"
	h5col "$f" /final/omega >"$d/w"
	paste "$d/k" "$d/m" "$d/r" "$d/y" "$d/vx" "$d/vy" "$d/w" | awk '
		$1 != 2 { n++; ke += 0.5 * $2 * ($5 * $5 + $6 * $6) + 0.25 * $2 * $3 * $3 * $7 * $7
			  sy += $4; s = sqrt($5 * $5 + $6 * $6); if (s > vm) vm = s }
		END { if (n) printf "%d %.6g %.10g %.6g\n", n, ke / n, sy / n, vm; else print "0 nan nan nan" }'
	rm -rf "$d"
}

# snap_mobile_y FILE : y of the mobile disks at each snapshot, one per line, snapshot
# after snapshot (from /particles/bed/position)
snap_mobile_y() {
	h5col "$1" /particles/bed/position/value | awk 'NR % 2 == 0'
}

# intruder_rows FILE : the intruder trajectory flattened as t, x, y, vx, vy, omega of
# each sample, one value per line (from /particles/intruder)
intruder_rows() {
	local g=/particles/intruder
	paste -d' ' <(h5col "$1" $g/position/time) <(h5col "$1" $g/position/value | paste -d' ' - -) \
		<(h5col "$1" $g/velocity/value | paste -d' ' - -) <(h5col "$1" $g/angular_velocity/value) | tr ' ' '\n'
}

# file_mean_y PARTICLE_FILE : mean y of the mobile disks of a text particle file
file_mean_y() {
	awk '!/^#/ && NF >= 4 && $4 != "wall" { n++; s += $2 } END { printf "%.10g\n", s / n }' "$1"
}

# no_nonfinite FILE : no nan/inf number anywhere in the dump (quoted strings such as the
# status name "nan" are not numbers)
no_nonfinite() {
	! h5dump -m %.17g "$1" | tail -n +2 | sed 's/"[^"]*"//g' | grep -Eiq '(^|[^a-z_])-?(nan|inf)([^a-z_]|$)'
}

# attr_val FILE NAME : value of a root attribute (quotes of strings removed); empty if absent
attr_val() {
	h5dump -m %.17g -a "/$2" "$1" 2>/dev/null | awk '
		/^ *\(0\): / { sub(/^ *\(0\): /, ""); if ($0 ~ /^".*"$/) $0 = substr($0, 2, length($0) - 2); print; exit }'
}
