//! [`Stats`] → a plain-text table for the terminal.

use std::fmt::Write;

use super::Stats;

/// The stats as text: per path, the pixel share of each kind, then per class the labelled
/// objects per frame (median), totals, ignore regions (and of those the faint ones, hidden
/// by darkness, fog or rain) and box-height quartiles; then the diversity of the variants
/// seen (facade, tree species, car body, person appearance and pose) and the positives and ignore
/// regions by reason.
pub fn table(stats: &Stats) -> String {
    let mut out = String::new();
    for path in &stats.paths {
        let _ = writeln!(
            out,
            "path {}: {} frames, {} pixels",
            path.name, path.frames, path.pixels
        );
        let _ = writeln!(out, "  {:<20} {:>8}", "kind", "pixels");
        for k in &path.kinds {
            let _ = writeln!(out, "  {:<20} {:>7.2} %", k.kind, k.share * 100.0);
        }
        let _ = writeln!(
            out,
            "  {:<20} {:>9} {:>9} {:>7} {:>6}   {:>5} {:>5} {:>5}",
            "class", "per frame", "labelled", "ignored", "faint", "h p25", "p50", "p75"
        );
        let rows = path.classes.iter().map(|c| {
            (
                c.name.as_str(),
                c.per_frame,
                c.labelled,
                c.ignored,
                c.faint,
                c.box_height,
            )
        });
        // A word is part of its plate: the all-classes row counts the plates.
        let plates = || {
            path.classes
                .iter()
                .filter(|c| c.name != super::path_stats::WORD_CATEGORY)
        };
        let all = (
            "(all labelled)",
            path.labelled_per_frame,
            plates().map(|c| c.labelled).sum(),
            plates().map(|c| c.ignored).sum(),
            plates().map(|c| c.faint).sum(),
            path.box_height,
        );
        for (name, per_frame, labelled, ignored, faint, height) in rows.chain([all]) {
            let h = height.map_or_else(
                || format!("{:>5} {:>5} {:>5}", "-", "-", "-"),
                |[a, b, c]| format!("{a:>5.1} {b:>5.1} {c:>5.1}"),
            );
            let _ = writeln!(
                out,
                "  {name:<20} {per_frame:>9.1} {labelled:>9} {ignored:>7} {faint:>6}   {h}"
            );
        }
        diversity_rows(&mut out, path);
        out.push('\n');
    }
    out
}

/// The diversity table (variants of each attribute seen) and the visibility line.
fn diversity_rows(out: &mut String, path: &super::PathStats) {
    let _ = writeln!(
        out,
        "  {:<20} {:>9} {:>8}   most used",
        "variant of", "instances", "variants"
    );
    for d in &path.diversity {
        let top = d.most_used.as_ref().map_or_else(
            || "-".to_owned(),
            |v| format!("{v} ({:.1} %)", d.most_used_share * 100.0),
        );
        let _ = writeln!(
            out,
            "  {:<20} {:>9} {:>8}   {top}",
            d.attribute, d.instances, d.variants
        );
    }
    let v = &path.visibility;
    let ignored: u64 = v.ignored.values().sum();
    let reasons: Vec<String> = v.ignored.iter().map(|(r, n)| format!("{r} {n}")).collect();
    let _ = writeln!(
        out,
        "  visibility: {} positives, {ignored} ignored ({})",
        v.positives,
        if reasons.is_empty() {
            "none".to_owned()
        } else {
            reasons.join(", ")
        }
    );
}
