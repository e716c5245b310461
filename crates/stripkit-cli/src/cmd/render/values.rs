//! The values of `stripkit render`'s flags: directions, angles, sizes, colours.

/// A direction `X,Y,Z`: three finite numbers.
pub fn parse_vec3(text: &str) -> Result<[f32; 3], String> {
    let parts: Vec<_> = text.split(',').map(|s| s.trim().parse::<f32>()).collect();
    match parts.as_slice() {
        [Ok(x), Ok(y), Ok(z)] if x.is_finite() && y.is_finite() && z.is_finite() => Ok([*x, *y, *z]),
        _ => Err(format!("`{text}` is not a direction: three finite numbers X,Y,Z, e.g. 0.3,0.4,1")),
    }
}

/// A vertical field of view: degrees from 1 to 120.
pub fn parse_fov(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(f) if (1.0..=120.0).contains(&f) => Ok(f),
        _ => Err(format!("`{text}` is not a field of view: degrees from 1 to 120")),
    }
}

/// A zoom factor from 1 to 100.
pub fn parse_zoom(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(z) if (1.0..=100.0).contains(&z) => Ok(z),
        _ => Err(format!("`{text}` is not a zoom: a factor from 1 to 100")),
    }
}

/// A morph weight from 0 to 1.
pub fn parse_unit(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(t) if (0.0..=1.0).contains(&t) => Ok(t),
        _ => Err(format!("`{text}` is not a morph weight: a number from 0 to 1")),
    }
}

/// Largest picture side.
pub const MAX_SIDE: u32 = 4096;

/// A picture size `WIDTHxHEIGHT`, each 16 to [`MAX_SIDE`].
pub fn parse_wh(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{text}` is not a picture size: WIDTHxHEIGHT, each 16 to {MAX_SIDE}, e.g. 800x800");
    let (w, h) = text
        .trim()
        .to_ascii_lowercase()
        .split_once('x')
        .map(|(w, h)| (w.trim().parse(), h.trim().parse()))
        .ok_or_else(bad)?;
    match (w, h) {
        (Ok(w), Ok(h)) if (16..=MAX_SIDE).contains(&w) && (16..=MAX_SIDE).contains(&h) => Ok((w, h)),
        _ => Err(bad()),
    }
}

/// A colour: `#rrggbb`, `rrggbb` or `R,G,B` (0 to 255 each).
pub fn parse_rgb(text: &str) -> Result<[u8; 3], String> {
    let bad = || format!("`{text}` is not a colour: #rrggbb, rrggbb or R,G,B (0 to 255 each)");
    let t = text.trim();
    if t.contains(',') {
        let parts: Vec<_> = t.split(',').map(|s| s.trim().parse::<u8>()).collect();
        return match parts.as_slice() {
            [Ok(r), Ok(g), Ok(b)] => Ok([*r, *g, *b]),
            _ => Err(bad()),
        };
    }
    let hex = t.strip_prefix('#').unwrap_or(t);
    if hex.len() != 6 || !hex.is_ascii() {
        return Err(bad());
    }
    let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).map_err(|_| bad());
    Ok([byte(0)?, byte(2)?, byte(4)?])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_parse_and_refuse() {
        assert_eq!(parse_vec3("0.3, 0.4,1"), Ok([0.3, 0.4, 1.0]));
        assert_eq!(parse_vec3("-1,0,-2"), Ok([-1.0, 0.0, -2.0]));
        assert!(parse_vec3("1,2").is_err() && parse_vec3("1,2,x").is_err() && parse_vec3("1,2,inf").is_err());
        assert_eq!(parse_wh("800x600"), Ok((800, 600)));
        assert_eq!(parse_wh("16X4096"), Ok((16, 4096)));
        for bad in ["0x10", "800", "15x800", "4097x10", "axb", "800x-1", ""] {
            assert!(parse_wh(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_rgb("#ff8000"), Ok([255, 128, 0]));
        assert_eq!(parse_rgb("0a0B0c"), Ok([10, 11, 12]));
        assert_eq!(parse_rgb("1, 2,255"), Ok([1, 2, 255]));
        for bad in ["#fff", "256,0,0", "gg0000", "1,2", "é1234"] {
            assert!(parse_rgb(bad).is_err(), "{bad}");
        }
        assert!(parse_zoom("0.5").is_err() && parse_zoom("101").is_err() && parse_zoom("2.5") == Ok(2.5));
        assert!(parse_fov("0.5").is_err() && parse_fov("121").is_err() && parse_fov("45").is_ok());
        assert!(parse_unit("1.5").is_err() && parse_unit("-0.1").is_err() && parse_unit("0.25") == Ok(0.25));
    }
}
