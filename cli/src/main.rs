//! `radiometry` command-line tool.

fn main() {
    println!("radiometry CLI: see `radiometry --help` (commands arrive with issue 3)");
}
