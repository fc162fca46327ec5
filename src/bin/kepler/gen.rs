//! `kepler gen`: the lab's stiff and extreme scenes, written as scene files.

use crate::output::emit;
use anyhow::Result;
use kepler::io::FileError;
use kepler::lab::stiff::{Family, generate, write};
use std::path::PathBuf;

/// Write a stiff scene (issue 15) of a family at stiffness K, placed by a seed: one OBJ file
/// per object and a scene file with its camera, in DIR; print the scene file's path.
/// `--list` prints the families with what K means and the values run.
#[derive(clap::Args)]
pub struct Args {
    /// The family (see --list).
    #[arg(long, value_parser = family, required_unless_present = "list")]
    family: Option<Family>,
    /// The stiffness; without it, every value of the family's list.
    #[arg(long, allow_negative_numbers = true)]
    k: Option<i32>,
    /// The seed of the placement.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The directory to write to (created if missing).
    #[arg(short, long, value_name = "DIR", default_value = ".")]
    out: PathBuf,
    /// List the families instead.
    #[arg(long, conflicts_with_all = ["family", "k"])]
    list: bool,
}

/// Writes the scenes asked for, or lists the families.
pub fn run(args: Args) -> Result<()> {
    let Some(family) = args.family.filter(|_| !args.list) else {
        return emit(&list());
    };
    let ks = args.k.map_or_else(|| family.parameters(false), |k| vec![k]);
    let mut paths = String::new();
    for k in ks {
        let stiff = generate(family, k, args.seed)?;
        let path = write(&stiff, &args.out)
            .map_err(|e| FileError::io(args.out.display().to_string(), e))?;
        paths += &format!("{}\n", path.display());
    }
    emit(&paths)
}

/// `--family`: a family's name.
fn family(name: &str) -> Result<Family, String> {
    Family::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Family::ALL.iter().map(|f| f.name()).collect();
        format!("unknown family (one of {})", names.join(", "))
    })
}

/// One line per family: its name, what K means, its range and the values run (quick ones in
/// brackets).
fn list() -> String {
    let mut text = format!(
        "{:<11} {:<30} {:<11} {}\n",
        "family", "k", "range", "values (quick)"
    );
    for f in Family::ALL {
        let values = |quick| {
            f.parameters(quick)
                .iter()
                .map(i32::to_string)
                .collect::<Vec<_>>()
                .join(" ")
        };
        let range = format!("{}..={}", f.range().start(), f.range().end());
        text += &format!(
            "{:<11} {:<30} {:<11} {} ({})\n",
            f.name(),
            f.parameter(),
            range,
            values(false),
            values(true)
        );
    }
    text
}
