//! `radiometry` command-line tool.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod spec;

fn main() {
    println!("radiometry CLI: see `radiometry --help` (commands arrive with issue 3)");
}
