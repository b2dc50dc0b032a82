#!/usr/bin/env bash
# Regenerates every Mitsuba 3 reference image in scenes/refs/ (see scenes/refs/README.md) and
# tests/real/refs/.
# Run from anywhere; needs Mitsuba 3.9.1 (scripts/install_mitsuba.sh).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
PYTHON="${PYTHON:-python3}"

"$PYTHON" scripts/mitsuba_ref.py scenes/cbox.xml -o scenes/refs/cbox_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/cs500_spheres.xml -o scenes/refs/cs500_spheres_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/envmap.xml -o scenes/refs/envmap_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/materials.xml -o scenes/refs/materials_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/veach_mis.xml -o scenes/refs/veach_mis_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# An area light with a bitmap radiance (tests/tests/textured_light_agreement.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/textured_light.xml -o scenes/refs/textured_light_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# Bump mapping on a sphere and a rectangle (tests/tests/bumpmap_agreement.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/bumpmap.xml -o scenes/refs/bumpmap_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# A projector and a textured spot light (tests/tests/projector_agreement.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/projector.xml -o scenes/refs/projector_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/spot_texture.xml -o scenes/refs/spot_texture_64x64_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# A filter with negative lobes (tests/tests/filter_agreement.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/cbox.xml -o scenes/refs/cbox_64x64_lanczos_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=lanczos --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/cbox.xml -o scenes/refs/cbox_64x64_gaussian_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=gaussian --variant scalar_rgb
# Splatted samples of unequal density (adaptive sampling; cli/tests/adaptive.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/veach_mis.xml -o scenes/refs/veach_mis_64x64_gaussian_mitsuba.exr \
    --spp 16384 --seed 0 -D res=64 -D rfilter=gaussian --variant scalar_rgb
# Participating media, rendered by volpath (tests/tests/media_agreement.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/media/fog_cbox.xml -o scenes/refs/fog_cbox_64x64_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/media/glass_sphere.xml -o scenes/refs/glass_sphere_64x64_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# A homogeneous medium with a grid albedo.
"$PYTHON" scripts/mitsuba_ref.py scenes/media/albedo_grid.xml -o scenes/refs/albedo_grid_64x64_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# Microflake media (the sggx phase function), absorbing only (see the scene's comment); grids by
# scripts/make_flakes_grid.py.
"$PYTHON" scripts/mitsuba_ref.py scenes/media/flakes.xml -o scenes/refs/flakes_64x64_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=box -D fibre_albedo=0 -D sheet_albedo=0 --variant scalar_rgb
# Chromatic media rendered by volpathmis, with rayleigh, tabphase and blendphase
# (tests/tests/volpathmis_agreement.rs).
"$PYTHON" scripts/mitsuba_ref.py scenes/media/chromatic_fog.xml -o scenes/refs/chromatic_fog_64x64_mitsuba.exr \
    --spp 8192 --seed 0 -D res=64 -D rfilter=box --variant scalar_rgb
# A heterogeneous medium (tests/tests/hetero_agreement.rs); its grid by scripts/make_smoke_grid.py.
"$PYTHON" scripts/mitsuba_ref.py scenes/media/smoke.xml -o scenes/refs/smoke_32x32_mitsuba.exr \
    --spp 8192 --seed 0 -D res=32 -D rfilter=box --variant scalar_rgb
# Benchmark references (tessera bench, scripts/mitsuba_bench.py): 128x128, box filter.
"$PYTHON" scripts/mitsuba_ref.py scenes/cbox.xml -o scenes/refs/cbox_128x128_mitsuba.exr \
    --spp 16384 --seed 0 -D res=128 -D rfilter=box --variant scalar_rgb
"$PYTHON" scripts/mitsuba_ref.py scenes/veach_mis.xml -o scenes/refs/veach_mis_128x128_mitsuba.exr \
    --spp 16384 --seed 0 -D res=128 -D rfilter=box --variant scalar_rgb
# The real corpus (tests/real/refs/LIST: sizes and sample counts; tests/real_agreement.rs).
"$PYTHON" scripts/mitsuba_real_refs.py --seed 0 --variant scalar_rgb
