#!/usr/bin/env bash
# regression.sh - the cross-built engine ($CROSS_SHAKE, run under $QEMU) on the
# regression scenes of tests/integration/regression.sh (`make cross-aarch64-regression`,
# docs/cross.md). Per scene and integrator:
#   regression.aarch64.CASE.PATH      on every kernel path the aarch64 engine has
#                                     (`shake --kernel-paths`, SHAKEBOX_KERNEL), the reduced
#                                     output (%.17g, tests/reference/regress.sh) equals the
#                                     committed x86-64 reference exactly; when it does not,
#                                     which datasets differ, in how many values and by how much
#   regression.aarch64.CASE.whole_file  on the path it picks, every dataset and every
#                                     attribute of the file equals those of the same run of
#                                     this machine's bin/shake
#                                     (h5diff, exact), but for what says where and when and
#                                     by which compiler it ran: /provenance, /parameters@output
#                                     and /@digest (a hash over every attribute, those too)
# Ends with "N passed, N failed"; exits non-zero on any failure.
cd "$(dirname "$0")/../.." || exit 1
QEMU=${QEMU:-qemu-aarch64 -L /usr/aarch64-linux-gnu}
CROSS_SHAKE=${CROSS_SHAKE:-$PWD/build/aarch64/bin/shake}
NATIVE_SHAKE=${NATIVE_SHAKE:-$PWD/bin/shake}
export SHAKE=$CROSS_SHAKE
. tests/integration/lib.sh
. tests/reference/regress.sh

# the engine under qemu, as regress_run calls it
cat >"$TMP/shake" <<EOF
#!/bin/sh
exec $QEMU "$CROSS_SHAKE" "\$@"
EOF
chmod +x "$TMP/shake"

# differing A B : per dataset of two reduced outputs, how many values differ and the
# largest absolute and relative difference
differing() {
	paste -d' ' "$1" "$2" | awk '
		$1 == "#" { if (n) report(); name = $2; n = 0; amax = 0; rmax = 0; next }
		$1 != $2 { n++; d = $1 - $2; if (d < 0) d = -d; if (d > amax) amax = d
			m = $2 < 0 ? -$2 : $2; if (m > 0 && d / m > rmax) rmax = d / m }
		function report() { printf "%s: %d values differ, max |diff| %.3g, max rel %.3g; ", name, n, amax, rmax }
		END { if (n) report() }'
}

# h5diff_differences H5DIFF_V_OUTPUT : the objects that differ, one a line, tab-separated:
# "dataset PATH - N", "attribute OBJECT NAME N", or "only-in-one-file PATH - -"; what
# records where, when and by which compiler the run was made is left out (/provenance,
# /parameters@output, and /@digest, which hashes every attribute, those too).
# h5diff -v writes "dataset: </final/x> and </final/x>" or "attribute: <NAME of <OBJ>> and
# ...", then any detail lines, then "N differences found"; its table of objects marks an
# object found in one file only with one x.
h5diff_differences() {
	awk '
		/^ +x +\// && NF == 2 { printf "only-in-one-file\t%s\t-\t-\n", $2; next }
		/^dataset: </ { kind = "dataset"; obj = $2; gsub(/[<>]/, "", obj); name = "-"; next }
		/^attribute: </ { kind = "attribute"; name = $2; sub(/^</, "", name); obj = $4; gsub(/[<>]/, "", obj); next }
		/^group *: / { kind = "group"; next }
		/[Nn]ot comparable/ { printf "not-comparable\t%s\t-\t-\n", obj; next }
		/differences found$/ && $1 + 0 > 0 && kind != "group" {
			if (kind == "attribute" && ((obj == "/" && name == "digest") || (obj == "/parameters" && name == "output") ||
			    obj ~ /^\/provenance/)) next
			printf "%s\t%s\t%s\t%d\n", kind, obj, name, $1 }' "$1"
}

# the kernel paths of the aarch64 engine that this (emulated) CPU runs
paths=$("$TMP/shake" --kernel-paths 2>"$TMP/paths.err" | awk '$2 == "yes" { printf "%s ", $1 }')
[ -n "$paths" ] || fail regression.aarch64.paths "shake --kernel-paths listed none: $(head -c 300 "$TMP/paths.err")"
# the one it picks by itself (`shake --version`: "kernel path: NAME (...)")
auto=$("$TMP/shake" --version 2>/dev/null | awk '$1 == "kernel" && $2 == "path:" { print $3 }')
case " $paths " in *" $auto "*) ;; *) fail regression.aarch64.auto_path "shake --version names the path '$auto', not one of: $paths" ;; esac

# compare ID CASE PATH OUT.h5 : run on kernel path PATH and compare with the reference
compare() {
	local id=$1 c=$2 path=$3 out=$4 t0=$SECONDS secs ref=tests/reference/$2.txt
	if ! SHAKEBOX_KERNEL=$path regress_run "$TMP/shake" "$c" "$out" >"$out.log" 2>&1; then
		fail "$id.run" "exit $?: $(head -c 300 "$out.log")"
		return
	fi
	secs=$((SECONDS - t0))
	regress_reduce "$out" >"$out.txt"
	if cmp -s "$out.txt" "$ref"; then
		ok "$id"
		echo "# $c on $path: $(wc -l <"$ref") values bit-identical to $ref (${secs}s under qemu)"
	elif [ "$(grep -c '^#' "$out.txt")" != "$(grep -c '^#' "$ref")" ] ||
		[ "$(wc -l <"$out.txt")" != "$(wc -l <"$ref")" ]; then
		fail "$id" "a different shape from $ref: $(wc -l <"$out.txt") lines, not $(wc -l <"$ref")"
	else
		fail "$id" "differs from $ref: $(differing "$out.txt" "$ref")"
	fi
}

for c in "${REGRESS_CASES[@]}"; do
	id=regression.aarch64.$c
	for path in $paths; do
		compare "$id.$path" "$c" "$path" "$TMP/$c.$path.h5"
	done
	[ -s "$TMP/$c.$auto.h5" ] || continue
	cp "$TMP/$c.$auto.h5" "$TMP/$c.h5"

	if [ ! -x "$NATIVE_SHAKE" ]; then
		fail "$id.whole_file" "no native engine at $NATIVE_SHAKE (run make)"
		continue
	fi
	if ! regress_run "$NATIVE_SHAKE" "$c" "$TMP/$c.x86.h5" >"$TMP/$c.x86.log" 2>&1; then
		fail "$id.whole_file.native_run" "exit $?: $(head -c 300 "$TMP/$c.x86.log")"
		continue
	fi
	h5diff -v "$TMP/$c.x86.h5" "$TMP/$c.h5" >"$TMP/$c.h5diff" 2>&1
	bad=""
	while IFS=$'\t' read -r kind obj name count; do
		case "$kind" in
		attribute)
			apath=${obj%/}/$name
			bad+="$apath: $(attr "$TMP/$c.x86.h5" "$apath") on x86-64, $(attr "$TMP/$c.h5" "$apath") on aarch64; "
			;;
		dataset) bad+="$obj: $count values differ; " ;;
		*) bad+="$obj: $kind; " ;;
		esac
	done < <(h5diff_differences "$TMP/$c.h5diff")
	n=$(grep -c '^dataset: ' "$TMP/$c.h5diff")
	if [ -z "$bad" ] && [ "$n" -gt 0 ]; then
		ok "$id.whole_file"
		echo "# $c: $n datasets and every physics attribute bit-identical to this machine's bin/shake"
	else
		fail "$id.whole_file" "differs from this machine's bin/shake ($n datasets compared): ${bad:-h5diff compared nothing: $(head -c 300 "$TMP/$c.h5diff")}"
	fi
done
echo "$NOK passed, $NFAIL failed"
finish
