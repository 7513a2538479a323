#!/bin/bash
# Measures the work estimate of tools/render/common/budget.rs against the CPU time (user + sys,
# GNU time) of every shipped scene, on both renderers where it applies, and of the two
# reproducers of tools/render/tests/data, and writes tools/render/budget_calibration.csv
# (docs/work_budget.md; the tests of both renderers check each row's estimate against it).
#
#     bash tools/render/calibrate.sh            # from the repository's root; a few minutes
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release -q -p diffraction-render --features stam --bins
out=tools/render/budget_calibration.csv
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
S=tools/render/scenes
D=tools/render/tests/data
W="--width 320 --spp 16"
rows=()
for s in fig4a fig4b fig5a fig5b fig6 $S/baselines/compare.toml; do rows+=("raytrace $s $W"); done
for s in fig4a fig4b fig5a fig5b fig6; do rows+=("raytrace $s $W --filter footprint"); done
for s in fig4a fig4b fig5a fig5b fig6 cd_area_light $S/presets/cd_preset.toml $S/presets/cd_rainbow.toml; do
    rows+=("pathtrace $s $W --integrator path")
done
for s in fig4a fig4b fig5a fig5b fig6 cd_area_light; do rows+=("pathtrace $s $W --integrator whitted"); done
rows+=("pathtrace $S/presets/cd_preset.toml --width 80 --spp 4 --integrator whitted")
rows+=("pathtrace $S/presets/cd_rainbow.toml --width 40 --spp 1 --integrator whitted")
rows+=("pathtrace $D/area_lights_exact.toml --integrator path")
rows+=("pathtrace $D/area_lights_exact.toml --width 8 --spp 1 --integrator whitted --budget 1000")
rows+=("raytrace $D/work_limits_multiply.toml --width 4 --height 4 --spp 1 --max-depth 4 --budget 1000")
rows+=("pathtrace $D/work_limits_multiply.toml --width 256 --height 256 --spp 4 --integrator path --budget 1000")
rows+=("pathtrace $D/work_limits_multiply.toml --width 1 --height 1 --spp 1 --max-depth 0 --integrator whitted --budget 1000")
{
    echo "# The work estimate (seconds of one core, --dry-run) against the measured CPU time (user + sys"
    echo "# of GNU time, one run) of each command, on $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg) at the start."
    echo "# Made by: bash tools/render/calibrate.sh ($(date -u +%Y-%m-%d))"
    echo "binary,arguments,estimate_s,cpu_s,ratio"
    for row in "${rows[@]}"; do
        read -r bin args <<<"$row"
        # shellcheck disable=SC2086
        est=$(./target/release/$bin $args --dry-run --out "$tmp/x.png" |
            sed -n 's/.*estimated work \([^ ]*\) s of one core.*/\1/p')
        # shellcheck disable=SC2086
        /usr/bin/time -f "%U %S" -o "$tmp/time" ./target/release/$bin $args --quiet --out "$tmp/x.png"
        read -r user sys <"$tmp/time"
        cpu=$(awk -v u="$user" -v s="$sys" 'BEGIN { printf "%.2f", u + s }')
        ratio=$(awk -v e="$est" -v c="$cpu" 'BEGIN { printf "%.2f", e / c }')
        echo "$bin,$args,$est,$cpu,$ratio"
    done
} >"$out.tmp"
mv "$out.tmp" "$out"
column -s, -t <"$out" | tail -n +4
