//! A GLB container written and split here, independently of the library's reader and
//! writer, so that tests can build hostile or exact files and look inside outputs.

use serde_json::Value;

/// The GLB file of `json` and the binary chunk `bin` (both padded to 4 bytes, the
/// JSON with spaces, as the container asks).
pub fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut text = serde_json::to_vec(json).expect("JSON encodes");
    text.resize(text.len().next_multiple_of(4), b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().next_multiple_of(4), 0);
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((28 + text.len() + bin.len()) as u32).to_le_bytes());
    out.extend((text.len() as u32).to_le_bytes());
    out.extend(0x4E4F_534Au32.to_le_bytes());
    out.extend(&text);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(0x004E_4942u32.to_le_bytes());
    out.extend(&bin);
    out
}

/// The JSON and binary chunk of a GLB file (an empty chunk when it has none); panics
/// on a file that is not a well-formed GLB, length included.
pub fn unglb(data: &[u8]) -> (Value, Vec<u8>) {
    let u = |o: usize| u32::from_le_bytes(data[o..o + 4].try_into().unwrap()) as usize;
    assert_eq!(&data[..4], b"glTF");
    assert_eq!(u(8), data.len());
    let json_len = u(12);
    let json = serde_json::from_slice(&data[20..20 + json_len]).expect("the JSON chunk parses");
    let bin_at = 20 + json_len;
    let bin = if bin_at < data.len() { data[bin_at + 8..bin_at + 8 + u(bin_at)].to_vec() } else { Vec::new() };
    (json, bin)
}
