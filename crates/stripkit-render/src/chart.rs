//! Charts as SVG text from plain series (no meshes or strips): the strip bar of the
//! culling figures.

use std::fmt::Write as _;
use std::ops::Range;

/// The strip bar (the constrained single-strip paper's Fig. 18): a buffer of `length`
/// elements as a horizontal band 1200 pixels wide, light grey, with the `spans` drawn
/// dark (each at least 0.3 pixels wide), a red tick at each of `marks` (element
/// positions, e.g. where strips start) and `heading` (escaped) above it.
pub fn strip_bar(length: usize, spans: &[Range<u32>], marks: &[u32], heading: &str) -> String {
    let (w, h, top) = (1200.0f64, 48.0f64, 28.0f64);
    let len = length.max(1) as f64;
    let x = |i: u32| i as f64 / len * w;
    let mut s = String::new();
    let _ = write!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}">
<rect width="100%" height="100%" fill="white"/>
<text x="0" y="18" font-family="sans-serif" font-size="14">{}</text>
<rect x="0" y="{top}" width="{w}" height="{h}" fill="#d8d8d8"/>
"##,
        w,
        top + h + 4.0,
        w,
        top + h + 4.0,
        xml_escape(heading),
    );
    for r in spans {
        let _ = writeln!(
            s,
            r##"<rect x="{:.3}" y="{top}" width="{:.3}" height="{h}" fill="#202020"/>"##,
            x(r.start),
            (x(r.end) - x(r.start)).max(0.3)
        );
    }
    for &o in marks {
        let _ = writeln!(s, r##"<line x1="{0:.3}" x2="{0:.3}" y1="{1}" y2="{2}" stroke="#d02020" stroke-width="1"/>"##, x(o), top - 3.0, top + h + 3.0);
    }
    s.push_str("</svg>\n");
    s
}

/// `text` with XML's special characters escaped.
fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bar_draws_spans_and_marks_and_escapes_the_heading() {
        let svg = strip_bar(100, &[10..20, 50..51], &[40], "a <b> & c");
        assert_eq!(svg.matches("fill=\"#202020\"").count(), 2);
        assert!(svg.contains(r#"<rect x="120.000" y="28" width="120.000""#));
        assert!(svg.contains(r#"<line x1="480.000" x2="480.000""#));
        assert!(svg.contains("a &lt;b&gt; &amp; c") && svg.ends_with("</svg>\n"));
    }
}
