//! A small Rust lexer for the tidy rules: separates code from comments and
//! string literals, keeping line numbers.

/// A source file split into code and comments.
#[derive(Debug, Default)]
pub struct Lexed {
    /// The file with every comment and string or char literal replaced by
    /// spaces (newlines kept), so words found in it are code.
    pub code: String,
    /// Every comment (line or block, doc or not) with its 1-based line.
    pub comments: Vec<(usize, String)>,
}

/// Splits `text` in one pass: `//` and nested `/* */` comments, `"..."`
/// strings with escapes, raw strings `r#"..."#` (any number of `#`), byte
/// and C strings, char literals told apart from lifetimes. O(length).
pub fn lex(text: &str) -> Lexed {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Lexed { code: String::with_capacity(text.len()), comments: Vec::new() };
    let (mut i, mut line) = (0, 1);
    while i < chars.len() {
        let end = match chars[i] {
            '/' if chars.get(i + 1) == Some(&'/') => line_comment(&chars, i),
            '/' if chars.get(i + 1) == Some(&'*') => block_comment(&chars, i),
            '"' => quoted(&chars, i + 1, '"'),
            'r' | 'b' | 'c' if !ident_before(&chars, i) => match raw_string(&chars, i) {
                Some(end) => end,
                None => {
                    out.code.push(chars[i]);
                    i += 1;
                    continue;
                }
            },
            '\'' => match char_literal(&chars, i) {
                Some(end) => end,
                None => {
                    // A lifetime or label: code.
                    out.code.push('\'');
                    i += 1;
                    continue;
                }
            },
            c => {
                out.code.push(c);
                line += usize::from(c == '\n');
                i += 1;
                continue;
            }
        };
        let token: String = chars[i..end].iter().collect();
        if chars[i] == '/' {
            out.comments.push((line, token.clone()));
        }
        for c in token.chars() {
            out.code.push(if c == '\n' { '\n' } else { ' ' });
        }
        line += token.matches('\n').count();
        i = end;
    }
    out
}

fn ident_before(chars: &[char], i: usize) -> bool {
    i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_')
}

fn line_comment(chars: &[char], i: usize) -> usize {
    chars[i..].iter().position(|&c| c == '\n').map_or(chars.len(), |p| i + p)
}

fn block_comment(chars: &[char], mut i: usize) -> usize {
    let mut depth = 0;
    while i < chars.len() {
        if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
            depth += 1;
            i += 2;
        } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return i;
            }
        } else {
            i += 1;
        }
    }
    chars.len()
}

/// The end (after the closing quote) of a literal whose body starts at `i`.
fn quoted(chars: &[char], mut i: usize, quote: char) -> usize {
    while i < chars.len() {
        match chars[i] {
            '\\' => i += 2,
            c if c == quote => return i + 1,
            _ => i += 1,
        }
    }
    chars.len()
}

/// `r"..."`, `r#"..."#`, `b"..."`, `br#"..."#`, `c"..."` starting at `i`.
fn raw_string(chars: &[char], i: usize) -> Option<usize> {
    let mut j = i + 1;
    if chars[i] != 'r' && chars.get(j) == Some(&'r') {
        j += 1;
    }
    let raw = chars[i] == 'r' || j == i + 2;
    if !raw {
        return (chars.get(j) == Some(&'"')).then(|| quoted(chars, j + 1, '"'));
    }
    let hashes = chars[j..].iter().take_while(|&&c| c == '#').count();
    j += hashes;
    if chars.get(j) != Some(&'"') {
        return None;
    }
    let close: Vec<char> = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
    let body = j + 1;
    Some(
        chars[body..]
            .windows(close.len())
            .position(|w| w == close.as_slice())
            .map_or(chars.len(), |p| body + p + close.len()),
    )
}

/// A char literal at `i` (`'a'`, `'\n'`, `'\u{1F600}'`), or `None` for a
/// lifetime or label.
fn char_literal(chars: &[char], i: usize) -> Option<usize> {
    match chars.get(i + 1)? {
        '\\' => Some(quoted(chars, i + 1, '\'')),
        _ if chars.get(i + 2) == Some(&'\'') => Some(i + 3),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::lex;

    #[test]
    fn comments_and_literals_are_not_code() {
        let text = "let a = \"unsafe // no\"; // unsafe here\n/* unsafe /* nested */ still */ unsafe {}\n\
                    let r = r#\"un\"safe\"#; let c = '\"'; fn f<'a>(x: &'a u8) {}\nlet q = '\\'';";
        let l = lex(text);
        assert_eq!(l.code.matches("unsafe").count(), 1, "{}", l.code);
        assert!(l.code.contains("fn f<'a>(x: &'a u8)"), "{}", l.code);
        assert_eq!(l.comments.len(), 2);
        assert_eq!(l.comments[0], (1, "// unsafe here".to_string()));
        assert_eq!(l.comments[1].0, 2);
        assert_eq!(l.code.lines().count(), text.lines().count());
    }
}
