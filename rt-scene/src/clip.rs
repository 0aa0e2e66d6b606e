//! Words, values and paths quoted from a file, cut to a length an error
//! line can hold: a refusal is one short line however long the file makes
//! what it quotes.

/// `text` (a word or value quoted from a file) cut to a length an error
/// line can hold.
pub fn clip(text: &str) -> String {
    clip_to(text, 48)
}

/// `path` as an error line shows it: a path built from a file's URI is as
/// long as the file makes it.
pub fn clip_path(path: &std::path::Path) -> String {
    clip_to(&path.display().to_string(), 200)
}

fn clip_to(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        Some((i, _)) => format!("{}...", &text[..i]),
        None => text.to_string(),
    }
}

/// `message` with every double-quoted span in it clipped ([`clip`]): the
/// `gltf` crate's JSON errors quote the offending value whole.
pub fn clip_quoted(message: &str) -> String {
    message
        .split('"')
        .enumerate()
        .map(|(i, part)| if i % 2 == 1 { clip(part) } else { part.to_string() })
        .collect::<Vec<_>>()
        .join("\"")
}
