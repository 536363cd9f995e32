#!/usr/bin/env bash
# Runs the firmware image under QEMU on a Cortex-M4F (mps2-an386) and a Cortex-M7 (mps2-an500) and compares every
# value with the same calls run natively (the host build of the same binary): they must be bit-identical.
# Installs what a fresh Debian machine needs (the thumbv7em-none-eabihf target, qemu-system-arm). Prints the
# instruction count and stack high-water mark of every call (M4F) and fails when a stack target is missed.
# Usage: firmware/run.sh   (from anywhere; outputs in firmware/target/qemu/)
set -euo pipefail
cd "$(dirname "$0")"
t=thumbv7em-none-eabihf
out=target/qemu
mkdir -p "$out"

rustup target add "$t" >/dev/null 2>&1 || {
    echo "firmware/run.sh: 'rustup target add $t' failed: the Cortex-M target is unavailable here" >&2
    exit 1
}
if ! command -v qemu-system-arm >/dev/null 2>&1; then
    as_root=""
    [ "$(id -u)" = 0 ] || as_root=sudo
    $as_root apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $as_root apt-get install -y -qq --no-install-recommends qemu-system-arm >/dev/null
fi
qemu-system-arm --version | head -n 1

cargo build --release --target "$t" -q
cargo build --release -q
img=target/$t/release/radiometry-firmware

./target/release/radiometry-firmware > "$out/host.txt"
for m in "mps2-an386 cortex-m4 m4f" "mps2-an500 cortex-m7 m7"; do
    set -- $m
    # -icount shift=0: virtual time advances a fixed step per instruction, so SysTick counts instructions
    # (the image calibrates ticks per instruction with a loop of known length). Exit status via semihosting.
    timeout 300 qemu-system-arm -M "$1" -cpu "$2" -nographic -monitor none -serial none \
        -semihosting-config enable=on,target=native -icount shift=0 -kernel "$img" > "$out/$3.txt" || {
        echo "firmware on $1 ($2) failed:"; tail -n 5 "$out/$3.txt"; exit 1; }
    grep -q '^DONE$' "$out/$3.txt" || { echo "firmware on $1 did not finish"; exit 1; }
    if ! diff <(grep '^VAL' "$out/host.txt") <(grep '^VAL' "$out/$3.txt") > "$out/$3.diff"; then
        echo "values on $1 ($2) differ from the native run:"; head -n 20 "$out/$3.diff"; exit 1
    fi
    echo "$1 ($2): $(grep -c '^VAL' "$out/$3.txt") values, all bit-identical to the native run"
done

echo
echo "Cortex-M4F (mps2-an386), opt-level \"s\": instructions per call, stack high-water mark (bytes)"
grep -E '^(CALIBRATION|PHASE-STACK)' "$out/m4f.txt"
awk '/^CASE/ { printf "  %-52s %10s insns %8s B\n", $2, $3, $4 }' "$out/m4f.txt"

# ALS <= 1 KB of stack; every integrator <= 8,000 B at budget 1,024 (the target: 8 KB), on the GGX albedo and
# through a cap light's integrand alike.
awk -v als=1024 -v integ="${FIRMWARE_INTEGRATOR_STACK_LIMIT:-8000}" '
    /^PHASE / { phase = $2 }
    /^CASE/ {
        s = $4; sub(/^>/, "", s); s += ($4 ~ /^>/)
        if (phase == "als" && s > als) { print "ALS stack " s " B > " als " B: " $2; bad = 1 }
        if (phase == "integrators" && s > integ) { print "integrator stack " s " B > " integ " B: " $2; bad = 1 }
    }
    END { exit bad }' "$out/m4f.txt"

# Flash and hidden f64: bare images (opt-level "s", LTO) calling a group of functions, minus the empty image.
echo
t=thumbv7em-none-eabihf
size_of() { cargo build --release --target "$t" -q --bin size --features "$1" && llvm-size "target/$t/release/size" | awk 'NR==2 {print $1 + $2}'; }
base=$(size_of "")
als_ggx=$(size_of "als ggx")
echo "flash: ALS + GGX eval/sample/pdf = $(( als_ggx - base )) bytes over the empty image ($base bytes); target <= 12 KiB"
[ $(( als_ggx - base )) -le 12288 ] || { echo "ALS + GGX exceeds 12 KiB"; exit 1; }
f32=$(size_of f32-paths)
helpers=$(llvm-nm "target/$t/release/size" | grep '__aeabi_d' || true)
echo "flash: the f32 paths (ALS, Lambertian, Phong family, GGX, spherical_direction, closed-form irradiances) = $(( f32 - base )) bytes; soft-float f64 helpers: $(printf '%s' "$helpers" | grep -c . || true)"
[ -z "$helpers" ] || { echo "soft-float f64 helpers (__aeabi_d*) in the f32 image:"; echo "$helpers"; exit 1; }
