//! The crates on a Cortex-M, and the same calls natively.
//!
//! Built for `thumbv7em-none-eabihf` this is a cortex-m-rt image: it runs every case of [`calls`], prints its
//! values over semihosting (`VAL name index hexbits value`), the instructions it took and the stack it used
//! (`CASE name instructions stack_bytes`), and exits through semihosting (status 0, or 1 on a panic). Built for
//! the host it prints the same `VAL` lines: `run.sh` compares the two.
#![cfg_attr(target_os = "none", no_std, no_main)]

mod calls;

use calls::{Out, Runner, V};

/// `VAL` lines: one per value (`f32`: 8 hex digits of its bits, `f64`: 16).
fn write_vals(name: &str, out: &Out, mut line: impl FnMut(core::fmt::Arguments)) {
    for (i, v) in out.values().iter().enumerate() {
        match *v {
            V::F32(x) => line(format_args!("VAL {name} {i} {:08x} {x:?}", x.to_bits())),
            V::F64(x) => line(format_args!("VAL {name} {i} {:016x} {x:?}", x.to_bits())),
            V::U64(x) => line(format_args!("VAL {name} {i} {x:x} {x}")),
        }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    struct Host;
    impl Runner for Host {
        fn phase(&mut self, name: &str) {
            println!("PHASE {name}");
        }
        fn case(&mut self, name: &str, f: &mut dyn FnMut() -> Out) {
            let out = f();
            write_vals(name, &out, |a| println!("{a}"));
        }
    }
    println!("TARGET host");
    calls::all(&mut Host);
    println!("DONE");
}

#[cfg(target_os = "none")]
mod target {
    use super::{Out, Runner, calls, write_vals};
    use cortex_m::peripheral::{SYST, syst::SystClkSource};
    use cortex_m_rt::entry;
    use cortex_m_semihosting::{debug, hprintln};

    /// SysTick counts down from `RELOAD` (24 bits) at the processor clock.
    const RELOAD: u32 = 0x00FF_FFFF;
    /// Iterations of the calibration loop (2 instructions each).
    const CAL_ITERS: u32 = 1_000_000;
    /// Cheap cases are timed over this many repetitions (SysTick ticks every few tens of instructions).
    const REPS: u32 = 64;
    /// A case is repeated when one run takes fewer ticks than this.
    const REPEAT_BELOW_TICKS: u32 = 2_000;

    /// Elapsed SysTick ticks from `start` to `end` (a down-counter, modulo 2²⁴; a case takes far fewer).
    fn ticks(start: u32, end: u32) -> u32 {
        start.wrapping_sub(end) & RELOAD
    }

    /// Instruction counts from SysTick under `qemu -icount shift=0`, where virtual time advances a fixed amount
    /// per instruction: SysTick ticks per instruction are calibrated against a loop of known length.
    struct Clock {
        /// Instructions (×2¹⁶) per tick.
        insn_per_tick_q16: u64,
        /// Instructions of an empty case (the dyn call and the two reads), subtracted from every count.
        overhead: u64,
    }

    impl Clock {
        fn now() -> u32 {
            SYST::get_current()
        }

        fn calibrate() -> Clock {
            let t0 = Self::now();
            stack::count_down(CAL_ITERS);
            let t = u64::from(ticks(t0, Self::now())).max(1);
            let mut c = Clock {
                insn_per_tick_q16: ((2 * u64::from(CAL_ITERS)) << 16) / t,
                overhead: 0,
            };
            c.overhead = c.time(&mut || Out::EMPTY).0;
            c
        }

        /// (instructions per run, runs timed) of `f`.
        fn time(&self, f: &mut dyn FnMut() -> Out) -> (u64, u32) {
            let t0 = Self::now();
            core::hint::black_box(f());
            let mut t = ticks(t0, Self::now());
            let mut reps = 1;
            if t < REPEAT_BELOW_TICKS {
                let t0 = Self::now();
                for _ in 0..REPS {
                    core::hint::black_box(f());
                }
                t = ticks(t0, Self::now());
                reps = REPS;
            }
            let insns = (u64::from(t) * self.insn_per_tick_q16 / u64::from(reps)) >> 16;
            (insns.saturating_sub(self.overhead), reps)
        }
    }

    struct Target {
        clock: Clock,
        /// Largest stack of any case in the current phase, and the phase's name.
        phase: Option<(&'static str, usize)>,
    }

    impl Target {
        fn end_phase(&mut self) {
            if let Some((name, max)) = self.phase.take() {
                hprintln!("PHASE-STACK {} {}", name, max);
            }
        }
    }

    impl Runner for Target {
        fn phase(&mut self, name: &str) {
            self.end_phase();
            hprintln!("PHASE {}", name);
            // Phase names are the literals of `calls`; keep a copy of the name only for the summary line.
            self.phase = Some((phase_name(name), 0));
        }

        fn case(&mut self, name: &str, f: &mut dyn FnMut() -> Out) {
            let used = stack::measure(&mut *f);
            let out = f();
            let (insns, reps) = self.clock.time(f);
            write_vals(name, &out, |a| hprintln!("{}", a));
            match used {
                Some(bytes) => hprintln!("CASE {} {} {} reps={}", name, insns, bytes, reps),
                None => hprintln!("CASE {} {} >{} reps={}", name, insns, stack::PAINT_BYTES, reps),
            }
            if let Some((_, max)) = self.phase.as_mut() {
                *max = (*max).max(used.unwrap_or(usize::MAX));
            }
        }
    }

    /// The `'static` name of a phase (the phases are fixed; an unknown one prints as "other").
    fn phase_name(name: &str) -> &'static str {
        ["als", "frame", "brdf", "lights", "integrators"]
            .into_iter()
            .find(|p| *p == name)
            .unwrap_or("other")
    }

    #[entry]
    fn main() -> ! {
        let ok = run();
        debug::exit(if ok {
            debug::EXIT_SUCCESS
        } else {
            debug::EXIT_FAILURE
        });
        loop {
            core::hint::spin_loop();
        }
    }

    fn run() -> bool {
        let Some(mut p) = cortex_m::Peripherals::take() else {
            return false;
        };
        p.SYST.set_clock_source(SystClkSource::Core);
        p.SYST.set_reload(RELOAD);
        p.SYST.clear_current();
        p.SYST.enable_counter();
        let clock = Clock::calibrate();
        hprintln!("TARGET thumbv7em-none-eabihf");
        hprintln!(
            "CALIBRATION instructions_per_tick={}.{:03} empty_case_instructions={}",
            clock.insn_per_tick_q16 >> 16,
            ((clock.insn_per_tick_q16 & 0xFFFF) * 1000) >> 16,
            clock.overhead
        );
        let mut t = Target { clock, phase: None };
        calls::all(&mut t);
        t.end_phase();
        hprintln!("DONE");
        true
    }

    #[panic_handler]
    fn panic(info: &core::panic::PanicInfo) -> ! {
        hprintln!("PANIC {}", info);
        debug::exit(debug::EXIT_FAILURE);
        loop {
            core::hint::spin_loop();
        }
    }

    /// Stack painting and the calibration loop: the only `unsafe` of the image.
    ///
    /// The stack grows down from the end of RAM toward `_stack_end` (cortex-m-rt: the end of `.bss`/`.uninit`).
    /// Before a case, the `PAINT_BYTES` below the current stack pointer (minus a `MARGIN` that the painting
    /// code's own frame and an exception entry may use) are filled with `PAINT`; after the case, the lowest
    /// word that no longer holds it is the case's high-water mark. Memory below the stack pointer belongs to
    /// no live object, so writing it is sound; `read_volatile`/`write_volatile` keep the accesses.
    mod stack {
        use super::Out;

        /// Bytes painted below the stack pointer (a deeper case reports "more than this").
        pub const PAINT_BYTES: usize = 512 * 1024;
        /// Bytes just below the stack pointer left unpainted (the painter's frame, an exception entry).
        const MARGIN: usize = 32;
        const PAINT: u32 = 0xC0DE_57AC;

        unsafe extern "C" {
            /// cortex-m-rt: the lowest address the stack may grow to.
            static _stack_end: u32;
        }

        /// Stack bytes `f` used below the caller's stack pointer, or `None` beyond the painted window.
        #[inline(never)]
        pub fn measure(f: &mut dyn FnMut() -> Out) -> Option<usize> {
            let sp = cortex_m::register::msp::read() as usize;
            let floor = core::ptr::addr_of!(_stack_end) as usize;
            let top = (sp - MARGIN) & !3;
            let bottom = top.saturating_sub(PAINT_BYTES).max((floor + 3) & !3);
            let mut a = bottom;
            while a < top {
                // SAFETY: `[bottom, top)` is RAM between the end of .bss and the stack pointer minus a margin
                // (no live object is there); aligned word writes.
                unsafe { core::ptr::write_volatile(a as *mut u32, PAINT) };
                a += 4;
            }
            core::hint::black_box(f());
            let mut a = bottom;
            // SAFETY: the same words, read back (aligned, in RAM).
            while a < top && unsafe { core::ptr::read_volatile(a as *const u32) } == PAINT {
                a += 4;
            }
            if a == bottom { None } else { Some(sp - a) }
        }

        /// A loop of exactly `2 n` instructions (`subs`, `bne`), the calibration of the instruction clock.
        #[inline(never)]
        pub fn count_down(n: u32) {
            // SAFETY: register-only arithmetic and a local branch; no memory, no stack.
            unsafe {
                core::arch::asm!(
                    "2:",
                    "subs {0}, {0}, #1",
                    "bne 2b",
                    inout(reg) n => _,
                    options(nomem, nostack),
                );
            }
        }
    }
}
