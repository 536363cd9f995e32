// Shared input decoding: the fuzzer's bytes become a stream of f32s (any bit
// pattern, then filtered to finite values, as the no-NaN contract covers
// finite input).
#![allow(dead_code)]
use radiometry::glam::Vec3;

pub struct Floats<'a>(pub &'a [u8]);

impl Floats<'_> {
    pub fn f32(&mut self) -> f32 {
        if self.0.len() < 4 {
            return 0.5;
        }
        let (a, rest) = self.0.split_at(4);
        self.0 = rest;
        let v = f32::from_le_bytes([a[0], a[1], a[2], a[3]]);
        if v.is_finite() { v } else { 0.25 }
    }
    pub fn unit(&mut self) -> f32 {
        let v = self.f32().abs();
        if v < 1.0 { v } else { v.fract() }
    }
    pub fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.f32(), self.f32(), self.f32())
    }
    pub fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((b, rest)) => {
                self.0 = rest;
                *b
            }
            None => 0,
        }
    }
}
