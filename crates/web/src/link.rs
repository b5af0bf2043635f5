//! Share links: the whole graph in the URL fragment, `#graph=<base64url of the deflate-compressed
//! RON>` (raw DEFLATE, RFC 1951, best compression; base64url without padding, RFC 4648 §5).
//! Nothing leaves the browser: the fragment is never sent to the server.

use base64::Engine as _;
use base64::engine::general_purpose::{URL_SAFE, URL_SAFE_NO_PAD};

/// The fragment key of a shared graph.
pub const KEY: &str = "graph=";

/// A decoded graph larger than this is refused (a link is a few kilobytes; this stops a
/// hostile link from inflating into gigabytes).
pub const MAX_GRAPH_BYTES: usize = 16 << 20;

/// Why a link did not give a graph (each message says what is wrong with the link, for the
/// dialog the page shows).
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum LinkError {
    /// The graph's text ends early: the link was cut short (copied in part, or shortened).
    #[error("the link is truncated: its graph ends early (was the whole link copied?)")]
    Truncated,
    /// The fragment is not base64url.
    #[error("the link is corrupted: its graph is not base64url text")]
    Base64,
    /// The bytes are not DEFLATE data.
    #[error("the link is corrupted: its graph is not deflate data")]
    Deflate,
    /// The graph inflates past [`MAX_GRAPH_BYTES`].
    #[error("the link's graph unpacks to over {} MB", MAX_GRAPH_BYTES >> 20)]
    TooLarge,
    /// The graph is not UTF-8 text.
    #[error("the link is corrupted: its graph is not UTF-8 text")]
    Utf8,
}

/// The fragment payload (after `#graph=`) for a graph's RON text.
pub fn encode(ron: &str) -> String {
    let packed = miniz_oxide::deflate::compress_to_vec(ron.as_bytes(), 10);
    URL_SAFE_NO_PAD.encode(packed)
}

/// The fragment of a share link, `#graph=…`.
pub fn fragment(ron: &str) -> String {
    format!("#{KEY}{}", encode(ron))
}

/// The RON text of a fragment payload (padding accepted).
pub fn decode(payload: &str) -> Result<String, LinkError> {
    let payload = payload.trim();
    let bytes = URL_SAFE_NO_PAD
        .decode(payload)
        .or_else(|unpadded| URL_SAFE.decode(payload).map_err(|_| unpadded))
        .map_err(|e| match e {
            // A length no base64 text has: the link was cut.
            base64::DecodeError::InvalidLength(_) | base64::DecodeError::InvalidLastSymbol(..) => {
                LinkError::Truncated
            }
            _ => LinkError::Base64,
        })?;
    use miniz_oxide::inflate::TINFLStatus;
    let text = miniz_oxide::inflate::decompress_to_vec_with_limit(&bytes, MAX_GRAPH_BYTES)
        .map_err(|e| match e.status {
            TINFLStatus::FailedCannotMakeProgress | TINFLStatus::NeedsMoreInput => {
                LinkError::Truncated
            }
            TINFLStatus::HasMoreOutput => LinkError::TooLarge,
            _ => LinkError::Deflate,
        })?;
    String::from_utf8(text).map_err(|_| LinkError::Utf8)
}

/// The shared graph of a URL fragment (`#graph=…`, with or without the `#`, among other
/// `&`-separated keys), if it has one.
pub fn from_fragment(fragment: &str) -> Option<Result<String, LinkError>> {
    let f = fragment.strip_prefix('#').unwrap_or(fragment);
    f.split('&')
        .find_map(|part| part.strip_prefix(KEY))
        .map(decode)
}

/// The value of `?example=<name>` in a URL query (with or without the `?`): the name of a
/// bundled graph, percent-decoding left out (gallery names are plain).
pub fn example_of_query(query: &str) -> Option<&str> {
    let q = query.strip_prefix('?').unwrap_or(query);
    q.split('&')
        .find_map(|part| part.strip_prefix("example="))
        .map(|n| n.trim_end_matches(".ron"))
        .filter(|n| !n.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_graph_round_trips_through_its_link() {
        let ron = "(nodes: [(id: \"a\", type: \"param.number\", value: 0.5)])\n";
        let f = fragment(ron);
        assert!(f.starts_with("#graph="));
        assert!(
            f.bytes()
                .skip(1)
                .all(|b| b.is_ascii_alphanumeric() || b"-_=".contains(&b)),
            "{f}"
        );
        assert_eq!(from_fragment(&f), Some(Ok(ron.to_string())));
        assert_eq!(
            from_fragment(&format!("x=1&{}", &f[1..])),
            Some(Ok(ron.into()))
        );
        assert_eq!(from_fragment("#other=1"), None);
    }

    #[test]
    fn hostile_links_are_refused_not_panicked_on() {
        assert_eq!(decode("***"), Err(LinkError::Base64));
        // Three zero bytes: a stored block's header and nothing after it.
        assert_eq!(decode("AAAA"), Err(LinkError::Truncated));
        // 0xff...: a reserved block type.
        assert_eq!(decode("____"), Err(LinkError::Deflate));
        // A bomb: 64 MB of zeros deflate into a few kilobytes.
        let bomb = miniz_oxide::deflate::compress_to_vec(&vec![0u8; 64 << 20], 10);
        assert!(bomb.len() < 200_000);
        assert_eq!(
            decode(&URL_SAFE_NO_PAD.encode(bomb)),
            Err(LinkError::TooLarge)
        );
        let not_text = miniz_oxide::deflate::compress_to_vec(&[0xff, 0xfe], 10);
        assert_eq!(
            decode(&URL_SAFE_NO_PAD.encode(not_text)),
            Err(LinkError::Utf8)
        );
    }

    #[test]
    fn a_link_cut_anywhere_says_it_is_truncated() {
        let ron = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../graphs/facade.ron"
        ))
        .expect("the gallery's facade");
        let payload = encode(&ron);
        assert_eq!(decode(&payload).as_deref(), Ok(ron.as_str()));
        for keep in [payload.len() / 10, payload.len() / 2, payload.len() - 7] {
            let cut = &payload[..keep];
            assert_eq!(decode(cut), Err(LinkError::Truncated), "cut at {keep}");
            assert!(LinkError::Truncated.to_string().contains("truncated"));
        }
    }

    #[test]
    fn example_names_come_from_the_query() {
        assert_eq!(
            example_of_query("?example=torus-monge"),
            Some("torus-monge")
        );
        assert_eq!(example_of_query("a=1&example=facade.ron"), Some("facade"));
        assert_eq!(example_of_query("?example="), None);
        assert_eq!(example_of_query(""), None);
    }
}
