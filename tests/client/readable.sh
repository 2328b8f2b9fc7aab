#!/bin/bash
# Output a person can read (issue 13, item 21), against a stand-in server with
# data of known shape (fake_results.py): plots whose y labels name the
# quantity, whose small series are not flattened by large ones and whose
# legends cover no curve; a progress bar for fetch on a terminal only; a study
# table of at most 100 columns with units and uniform numbers.
. "$(cd "$(dirname "$0")" && pwd)/fake_common.sh"
PC=$top_srcdir/tests/client/plot_check.py

# ------------------------------------------------------------ plot
# kinetic energy ~1e-3 J beside internal energy and external work ~10 J
cl plot "$FID" kinetic_energy internal_energy external_work -o "$TMP/energy.svg"
check "plot energies: exit 0" rc_is 0
check "plot: each y label names the quantity and its unit" "$PY" "$PC" svg "$TMP/energy.svg" labels
check "plot: 1e-3 J kinetic energy is not flattened by 10 J energies" \
    "$PY" "$PC" svg "$TMP/energy.svg" panels --spread kinetic_energy --spread internal_energy
check "plot: no legend over a frame or a curve" "$PY" "$PC" svg "$TMP/energy.svg" legend
check "plot: the energy panel's label is 'energy [J]'" grep -q '>energy \[J\]</text>' "$TMP/energy.svg"
# reaction force components 2e5 N and 15 N
cl plot "$FID" groups/right/reaction_force -o "$TMP/force.svg" --title "Reaction force"
check "plot reaction force (2e5 N beside 15 N): exit 0" rc_is 0
check "plot force: labels, panels, legend" bash -c "'$PY' '$PC' svg '$TMP/force.svg' labels &&
    '$PY' '$PC' svg '$TMP/force.svg' panels --spread 'groups/right/reaction_force[y]' &&
    '$PY' '$PC' svg '$TMP/force.svg' legend"
cl plot "$FID" groups/right/reaction_force:x --x groups/right/displacement:x -o "$TMP/fd.svg"
check "plot --x: both labels name quantity, owner and unit" bash -c "[ $RC = 0 ] &&
    grep -q '>reaction force x of groups/right \[N\]</text>' '$TMP/fd.svg' &&
    grep -q '>displacement x of groups/right \[m\]</text>' '$TMP/fd.svg'"
# --log: one log axis per unit; every curve inside its frame
cl plot "$FID" kinetic_energy internal_energy --log -o "$TMP/log.svg"
check "plot --log: exit 0, one frame for both energies, decade ticks" bash -c "[ $RC = 0 ] &&
    [ \$(grep -c 'class=\"frame\"' '$TMP/log.svg') = 1 ] && grep -q '>10<tspan[^>]*>-3</tspan>' '$TMP/log.svg' &&
    '$PY' '$PC' svg '$TMP/log.svg' panels && '$PY' '$PC' svg '$TMP/log.svg' labels"
cl plot "$FID" groups/right/displacement --log -o "$TMP/log0.svg"
check "plot --log: points <= 0 are left out and counted" bash -c "[ $RC = 0 ] &&
    grep -q 'displacement\[y\]: 0 points (101 points <= 0 left out of the log axis)' '$TMP/err'"

# ------------------------------------------------------------ fetch progress
# the stand-in sends 3 MiB files in 64 KiB slices 10 ms apart
cl fetch "$FID" -o "$TMP/dl"
check "fetch, stderr not a terminal: exactly the two result lines, no bar" bash -c "[ $RC = 0 ] &&
    printf '%s\n' '$TMP/dl/result.h5: 3145728 bytes' '$TMP/dl/result.xmf: 3145728 bytes' | cmp -s - '$TMP/err' &&
    ! grep -q \$'[\r\033]' '$TMP/out'"
if script -qec true /dev/null </dev/null >/dev/null 2>&1; then
    # script(1) gives the client a terminal; its stdout and stderr land in the typescript
    script -qec "'$CLIENT' fetch '$FID' -o '$TMP/dl-tty'" "$TMP/typescript" </dev/null >/dev/null 2>&1
    check "fetch on a terminal: a progress bar redrawn in place up to 100%" bash -c "
        grep -q \$'\rresult.h5  \\[#*\\.*\\] *[0-9]*%  .* of 3.0 MiB\033\\[K' '$TMP/typescript' &&
        grep -q \$'\rresult.xmf  \\[####################\\] 100%  3.0 MiB of 3.0 MiB' '$TMP/typescript' &&
        grep -q '$TMP/dl-tty/result.h5: 3145728 bytes' '$TMP/typescript' &&
        cmp -s '$TMP/dl/result.h5' '$TMP/dl-tty/result.h5'"
else
    echo "# skipped the terminal check: script(1) (util-linux) missing"
fi

# ------------------------------------------------------------ study table
TC=$top_srcdir/tests/client/table_check.py
cl study table "$FID"
check "study table: at most 100 columns, units in the header, numbers alike and aligned" bash -c "[ $RC = 0 ] &&
    '$PY' '$TC' '$TMP/out' 100 'end [s]' vmax peak_force 'wall [s]' 'speed [1/s]'"
check "study table: 4 rows under one header; what was shortened said on stderr" bash -c "
    [ \$(wc -l <'$TMP/out') = 5 ] && grep -q '^ *2  4b577b8c  failed ' '$TMP/out' &&
    grep -q 'job ids shortened to 8 characters' '$TMP/err'"
cl study table ffffffffffffffffffffffffffffffff
check "study table with 16 outputs: blocks of at most 100 columns, each starting with seq" bash -c "[ $RC = 0 ] &&
    '$PY' '$TC' '$TMP/out' 100 output_00_of_the_study output_05_of_the_study output_11_of_the_study 'wall [s]'"

finish
