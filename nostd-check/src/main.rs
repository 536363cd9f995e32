//! no_std link check: see Cargo.toml.
#![no_std]
#![no_main]

use core::hint::black_box;
use radiometry::glam::Vec3;
use radiometry::{Brdf, Frame};

// Link the C runtime (for `__libc_start_main`, `memcpy`, `memset`) so the
// release build links and runs on x86_64 Linux.
#[link(name = "c")]
unsafe extern "C" {}

#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

struct Toy;
impl Brdf for Toy {
    type Spectrum = f32;
    fn eval(&self, wi: Vec3, wo: Vec3) -> f32 {
        if wi.z > 0.0 && wo.z > 0.0 { 0.3 } else { 0.0 }
    }
}

fn exercise<B: Brdf>(b: &B, acc: &mut f32) {
    let wo = black_box(Vec3::new(0.3, 0.1, 0.9).normalize());
    let wi = black_box(Vec3::new(-0.2, 0.4, 0.8).normalize());
    *acc += b.eval(wi, wo).average();
    *acc += b.pdf(wi, wo);
    if let Some(s) = b.sample(wo, black_box([0.25, 0.75])) {
        *acc += s.pdf + s.weight.average();
    }
}

use radiometry::Spectrum;

#[unsafe(no_mangle)]
pub extern "C" fn main(_argc: i32, _argv: *const *const u8) -> i32 {
    let mut acc = 0.0f32;
    exercise(&Toy, &mut acc);
    let f = Frame::from_normal(black_box(Vec3::new(0.0, 1.0, 1.0)));
    if let Some(f) = f {
        acc += f.to_local(Vec3::X).x;
    }
    // PLUGINS
    if acc.is_finite() { 0 } else { 1 }
}
