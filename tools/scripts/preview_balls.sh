#!/bin/sh
# Renders the material balls shown in docs/cli.md ("Material previews") and
# docs/colour.md into cli/results/balls/: the grey specs in the daylight scene
# (white sun, pale blue sky, grey-brown ground) as RGB, the typed colour
# materials in RGB and spectrally, and the camera-vs-observer pictures; 160 px,
# the default samples; prints the time of each (and the camera reports) and
# the CPU. Run from anywhere: tools/scripts/preview_balls.sh
set -eu
cd "$(dirname "$0")/../.."
cargo build --release -p radiometry-cli
out=cli/results/balls
mkdir -p "$out"
light="--daylight --sky-radiance 0.5"
ball() {
    name=$1
    shift
    echo "== $name: radiometry preview $*"
    # shellcheck disable=SC2086
    ./target/release/radiometry preview "$@" --size 160 --no-progress --out "$out/$name.png"
}
# shellcheck disable=SC2086
{
ball lambertian 'lambertian(albedo=0.8)' $light
ball eon-s0 'eon(rho=0.8, sigma=0)' $light
ball eon-s0.5 'eon(rho=0.8, sigma=0.5)' $light
ball eon-s1 'eon(rho=0.8, sigma=1)' $light
ball ggx-a0.1 'ggx(alpha=0.1)' $light
ball ggx-a0.5 'ggx(alpha=0.5)' $light
ball plastic 'coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))' $light
ball sheen 'sheen(color=1, roughness=0.5) + lambertian(albedo=0.3)' $light
ball coated-metal 'coated(ggx(alpha=0.05, fresnel=dielectric(eta=1.5)), ggx(alpha=0.3, fresnel=conductor(eta=0.2, k=3)))' $light
ball openpbr 'openpbr' $light
ball gold --material gold $light
ball copper --material copper $light
ball red-plastic --material red-plastic $light
ball gold-spectral --material gold --spectral 4 $light
ball copper-spectral --material copper --spectral 4 $light
ball red-plastic-spectral --material red-plastic --spectral 4 $light
ball camera-bayer-d65 --material red-plastic --camera bayer --light d65
ball camera-prism-d65 --material red-plastic --camera prism --light d65
ball camera-stacked-d65 --material red-plastic --camera stacked --light d65
ball camera-bayer-a --material gold --camera bayer --light a
ball camera-bayer-d65-dark --material red-plastic --camera bayer --light d65 --camera-exposure 0.01
python3 tools/scripts/studio_hdr.py
studio="--env $out/studio.hdr --sun-irradiance 0"
ball studio-gold --material gold $studio
ball studio-copper --material copper $studio
ball studio-red-plastic --material red-plastic $studio
ball studio-mirror 'ggx(alpha=0.02)' $studio
}
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) hardware threads"
