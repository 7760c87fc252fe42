//! The GLB container (header, JSON chunk, one BIN chunk) and base64 data URIs.
//!
//! GLB rules kept on reading: magic `glTF`, version 2, a length field equal to the bytes
//! present (a longer file is refused as well as a shorter one), the first chunk JSON, at most
//! one BIN chunk and it second, every chunk length a multiple of 4; chunks of other types are
//! skipped (the specification says so). On writing: JSON padded with spaces and BIN with zeros
//! to 4 bytes, the BIN chunk left out when the document has no binary data.

use crate::GltfError;

const MAGIC: &[u8; 4] = b"glTF";
const JSON: u32 = 0x4E4F_534A;
const BIN: u32 = 0x004E_4942;

/// Whether `bytes` start like a GLB container.
pub(crate) fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

fn u32_at(bytes: &[u8], at: usize) -> Result<u32, GltfError> {
    match bytes.get(at..at + 4) {
        Some(b) => Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        None => Err(GltfError::Truncated {
            offset: at as u64,
            needed: 4,
            available: bytes.len().saturating_sub(at) as u64,
        }),
    }
}

/// The JSON chunk and the BIN chunk (if any) of a GLB.
pub(crate) fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), GltfError> {
    if bytes.len() < 4 || !is_glb(bytes) {
        let mut found = [0u8; 4];
        for (f, b) in found.iter_mut().zip(bytes) {
            *f = *b;
        }
        return Err(GltfError::BadMagic { found });
    }
    let version = u32_at(bytes, 4)?;
    if version != 2 {
        return Err(GltfError::BadVersion(version));
    }
    let length = u64::from(u32_at(bytes, 8)?);
    if length > bytes.len() as u64 {
        return Err(GltfError::Truncated {
            offset: 0,
            needed: length,
            available: bytes.len() as u64,
        });
    }
    if length < bytes.len() as u64 {
        return Err(GltfError::Chunk {
            offset: 8,
            reason: format!(
                "the header's length is {length}, but the file has {} bytes",
                bytes.len()
            ),
        });
    }
    let mut at = 12usize;
    let mut json = None;
    let mut bin = None;
    let mut index = 0;
    while at < bytes.len() {
        let len = u32_at(bytes, at)? as usize;
        let kind = u32_at(bytes, at + 4)?;
        let start = at + 8;
        let available = bytes.len() - start.min(bytes.len());
        if len > available {
            return Err(GltfError::Truncated {
                offset: start as u64,
                needed: len as u64,
                available: available as u64,
            });
        }
        let chunk = &bytes[start..start + len];
        let fail = |reason: &str| GltfError::Chunk {
            offset: at as u64,
            reason: reason.into(),
        };
        if len % 4 != 0 {
            return Err(fail("its length is not a multiple of 4"));
        }
        match (index, kind) {
            (0, JSON) => json = Some(chunk),
            (0, _) => return Err(fail("the first chunk must be JSON")),
            (1, BIN) => bin = Some(chunk),
            (_, BIN) => return Err(fail("a BIN chunk may only be the second chunk")),
            (_, JSON) => return Err(fail("a second JSON chunk")),
            _ => {}
        }
        index += 1;
        at = start + len;
    }
    let json = json.ok_or(GltfError::Truncated {
        offset: 12,
        needed: 8,
        available: 0,
    })?;
    Ok((json, bin))
}

/// A GLB of `json` and `bin` (no BIN chunk when `bin` is empty).
pub(crate) fn join_glb(json: &[u8], bin: &[u8]) -> Result<Vec<u8>, GltfError> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + if bin.is_empty() { 0 } else { 8 + bin_len };
    let total32 = u32::try_from(total).map_err(|_| GltfError::TooLarge(total as u64))?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total32.to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(&JSON.to_le_bytes());
    out.extend_from_slice(json);
    out.resize(out.len() + pad(json.len()), b' ');
    if !bin.is_empty() {
        out.extend_from_slice(&(bin_len as u32).to_le_bytes());
        out.extend_from_slice(&BIN.to_le_bytes());
        out.extend_from_slice(bin);
        out.resize(out.len() + pad(bin.len()), 0);
    }
    Ok(out)
}

const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 with padding.
pub(crate) fn base64_encode(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Standard base64, padding optional; `None` for any other character or a bad length.
pub(crate) fn base64_decode(text: &str) -> Option<Vec<u8>> {
    let text = text.trim_end_matches('=').as_bytes();
    if text.len() % 4 == 1 {
        return None;
    }
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let value = |c: u8| ALPHABET.iter().position(|&a| a == c).map(|v| v as u32);
    for chunk in text.chunks(4) {
        let mut n = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            n |= value(c)? << (18 - 6 * k);
        }
        let bytes = n.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Some(out)
}

/// The bytes of a `data:` URI with base64 content, or why not.
pub(crate) fn data_uri(uri: &str) -> Result<Vec<u8>, String> {
    let rest = &uri["data:".len()..];
    let (header, data) = rest
        .split_once(',')
        .ok_or_else(|| "a data URI without a comma".to_string())?;
    if !header.ends_with(";base64") {
        return Err(format!("data URI {header:?} is not base64"));
    }
    base64_decode(data).ok_or_else(|| "the data URI's base64 is malformed".into())
}

/// `%XX` escapes of a relative URI decoded (other characters as written).
pub(crate) fn percent_decode(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = uri
                .get(i + 1..i + 3)
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("bad escape at character {i} of {uri:?}"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("{uri:?} is not UTF-8 once decoded"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trip() {
        for n in 0..20 {
            let bytes: Vec<u8> = (0..n).map(|i| (i * 37 + 11) as u8).collect();
            let text = base64_encode(&bytes);
            assert_eq!(text.len() % 4, 0);
            assert_eq!(base64_decode(&text).unwrap(), bytes);
        }
        assert_eq!(base64_encode(b"Man"), "TWFu");
        assert_eq!(base64_encode(b"Ma"), "TWE=");
        assert_eq!(base64_decode("TWE").unwrap(), b"Ma");
        assert!(base64_decode("TW!u").is_none());
        assert!(base64_decode("T").is_none());
    }

    #[test]
    fn glb_round_trip_and_refusals() {
        let glb = join_glb(b"{\"a\":1}", &[1, 2, 3]).unwrap();
        assert_eq!(glb.len() % 4, 0);
        let (json, bin) = split_glb(&glb).unwrap();
        assert_eq!(json, b"{\"a\":1} ");
        assert_eq!(bin.unwrap(), &[1, 2, 3, 0]);
        assert!(matches!(
            split_glb(&glb[..glb.len() - 4]),
            Err(GltfError::Truncated { offset: 0, .. })
        ));
        let mut bad = glb.clone();
        bad[0] = b'x';
        assert!(matches!(split_glb(&bad), Err(GltfError::BadMagic { found }) if &found == b"xlTF"));
        let mut v1 = glb.clone();
        v1[4] = 1;
        assert!(matches!(split_glb(&v1), Err(GltfError::BadVersion(1))));
    }

    #[test]
    fn percent_escapes() {
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decode("a%2").is_err());
    }
}
