#!/bin/sh
# Renders the row of material balls shown in docs/cli.md ("Material previews")
# into cli/results/balls/, 160 px, the default samples, sun and sky; prints the
# time of each and the CPU. Run from anywhere: tools/scripts/preview_balls.sh
set -eu
cd "$(dirname "$0")/../.."
cargo build --release -p radiometry-cli
out=cli/results/balls
mkdir -p "$out"
ball() {
    ./target/release/radiometry preview "$2" --size 160 --no-progress --out "$out/$1.png"
}
ball lambertian 'lambertian(albedo=0.8)'
ball eon-s0 'eon(rho=0.8, sigma=0)'
ball eon-s0.5 'eon(rho=0.8, sigma=0.5)'
ball eon-s1 'eon(rho=0.8, sigma=1)'
ball ggx-a0.1 'ggx(alpha=0.1)'
ball ggx-a0.5 'ggx(alpha=0.5)'
ball plastic 'coated(ggx(alpha=0.1, fresnel=dielectric(eta=1.5)), lambertian(albedo=0.8))'
ball sheen 'sheen(color=1, roughness=0.5) + lambertian(albedo=0.3)'
ball coated-metal 'coated(ggx(alpha=0.05, fresnel=dielectric(eta=1.5)), ggx(alpha=0.3, fresnel=conductor(eta=0.2, k=3)))'
ball openpbr 'openpbr'
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), $(nproc) hardware threads"
