//! A small RON reader that keeps the line and column of every value, so that graph files can report
//! problems where they are. It reads the RON subset graph files use: structs (named or not), tuples,
//! lists, maps, strings (plain and raw), chars, numbers (including `inf` and `NaN`), booleans, `Some`,
//! `None`, identifiers, comments and `#![enable(..)]` headers.

use std::fmt;

/// A 1-based line and column (columns count characters).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    PartialOrd,
    Ord,
    Default,
    serde::Serialize,
    serde::Deserialize,
)]
pub struct Pos {
    /// Line, from 1.
    pub line: u32,
    /// Column, from 1.
    pub col: u32,
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// A parsed value with the position where it starts.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// Where the value starts.
    pub pos: Pos,
    /// What it is.
    pub kind: Kind,
}

/// A struct field name with its position.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// The name.
    pub name: String,
    /// Where it starts.
    pub pos: Pos,
}

/// The kinds of RON values.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// `true` / `false`.
    Bool(bool),
    /// An integer literal.
    Int(i64),
    /// A float literal (including `inf`, `NaN`).
    Float(f64),
    /// A string.
    Str(String),
    /// A character.
    Char(char),
    /// `()`.
    Unit,
    /// `None`.
    None,
    /// `Some(value)`.
    Some(Box<Node>),
    /// A bare identifier (unit struct or enum variant).
    Ident(String),
    /// `[a, b]`.
    List(Vec<Node>),
    /// `{k: v}`.
    Map(Vec<(Node, Node)>),
    /// `(a, b)` or `Name(a, b)`.
    Tuple(Option<String>, Vec<Node>),
    /// `(f: a)` or `Name(f: a)`.
    Struct(Option<String>, Vec<(Field, Node)>),
}

impl Kind {
    /// A short description for messages ("a string", "a list", …).
    pub fn describe(&self) -> &'static str {
        match self {
            Kind::Bool(_) => "a boolean",
            Kind::Int(_) => "an integer",
            Kind::Float(_) => "a number",
            Kind::Str(_) => "a string",
            Kind::Char(_) => "a character",
            Kind::Unit => "()",
            Kind::None => "None",
            Kind::Some(_) => "Some(..)",
            Kind::Ident(_) => "an identifier",
            Kind::List(_) => "a list",
            Kind::Map(_) => "a map",
            Kind::Tuple(..) => "a tuple",
            Kind::Struct(..) => "a struct",
        }
    }
}

impl Node {
    /// The number, for integers and floats.
    pub fn as_f64(&self) -> Option<f64> {
        match self.kind {
            Kind::Int(i) => Some(i as f64),
            Kind::Float(x) => Some(x),
            _ => None,
        }
    }

    /// The text, for strings.
    pub fn as_str(&self) -> Option<&str> {
        match &self.kind {
            Kind::Str(s) => Some(s),
            _ => None,
        }
    }

    /// The fields, for structs.
    pub fn fields(&self) -> Option<&[(Field, Node)]> {
        match &self.kind {
            Kind::Struct(_, fields) => Some(fields),
            _ => None,
        }
    }

    /// The items, for lists and tuples.
    pub fn items(&self) -> Option<&[Node]> {
        match &self.kind {
            Kind::List(items) | Kind::Tuple(_, items) => Some(items),
            _ => None,
        }
    }
}

/// A syntax error with its position.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseError {
    /// Where the problem is.
    pub pos: Pos,
    /// What is wrong.
    pub message: String,
}

/// Deepest nesting accepted (deeper input is an error, not a stack overflow).
const MAX_DEPTH: usize = 128;

/// Parses one RON value (the whole input).
pub fn parse(text: &str) -> Result<Node, ParseError> {
    let mut p = Parser {
        text,
        at: 0,
        line: 1,
        col: 1,
    };
    p.skip_trivia()?;
    p.skip_attributes()?;
    let value = p.value(0)?;
    p.skip_trivia()?;
    if p.at < p.text.len() {
        return Err(p.error("unexpected text after the end of the value"));
    }
    Ok(value)
}

/// Reads the text in place (a copy as `Vec<char>` took four bytes a byte: 228 MB for a 57 MB file).
struct Parser<'a> {
    text: &'a str,
    /// Byte offset of the next character.
    at: usize,
    line: u32,
    col: u32,
}

impl Parser<'_> {
    fn pos(&self) -> Pos {
        Pos {
            line: self.line,
            col: self.col,
        }
    }

    fn error(&self, message: impl Into<String>) -> ParseError {
        ParseError {
            pos: self.pos(),
            message: message.into(),
        }
    }

    /// The text from the next character on.
    fn rest(&self) -> &str {
        &self.text[self.at..]
    }

    fn peek(&self) -> Option<char> {
        self.rest().chars().next()
    }

    /// The character `k` characters ahead.
    fn peek_at(&self, k: usize) -> Option<char> {
        self.rest().chars().nth(k)
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.at += c.len_utf8();
        if c == '\n' {
            self.line += 1;
            self.col = 1;
        } else {
            self.col += 1;
        }
        Some(c)
    }

    fn expect(&mut self, c: char) -> Result<(), ParseError> {
        self.skip_trivia()?;
        match self.peek() {
            Some(d) if d == c => {
                self.bump();
                Ok(())
            }
            Some(d) => Err(self.error(format!("expected '{c}', found '{d}'"))),
            None => Err(self.error(format!("expected '{c}', found the end of the file"))),
        }
    }

    fn skip_trivia(&mut self) -> Result<(), ParseError> {
        loop {
            match (self.peek(), self.peek_at(1)) {
                (Some(c), _) if c.is_whitespace() => {
                    self.bump();
                }
                (Some('/'), Some('/')) => {
                    while let Some(c) = self.peek() {
                        if c == '\n' {
                            break;
                        }
                        self.bump();
                    }
                }
                (Some('/'), Some('*')) => {
                    let start = self.pos();
                    self.bump();
                    self.bump();
                    let mut depth = 1;
                    while depth > 0 {
                        match (self.peek(), self.peek_at(1)) {
                            (Some('*'), Some('/')) => {
                                self.bump();
                                self.bump();
                                depth -= 1;
                            }
                            (Some('/'), Some('*')) => {
                                self.bump();
                                self.bump();
                                depth += 1;
                            }
                            (Some(_), _) => {
                                self.bump();
                            }
                            (None, _) => {
                                return Err(ParseError {
                                    pos: start,
                                    message: "unterminated block comment".into(),
                                });
                            }
                        }
                    }
                }
                _ => return Ok(()),
            }
        }
    }

    /// Skips `#![enable(...)]` headers.
    fn skip_attributes(&mut self) -> Result<(), ParseError> {
        while self.peek() == Some('#') {
            self.bump();
            if self.peek() == Some('!') {
                self.bump();
            }
            self.expect('[')?;
            let mut depth = 1;
            while depth > 0 {
                match self.bump() {
                    Some('[') => depth += 1,
                    Some(']') => depth -= 1,
                    Some(_) => {}
                    None => return Err(self.error("unterminated attribute")),
                }
            }
            self.skip_trivia()?;
        }
        Ok(())
    }

    fn value(&mut self, depth: usize) -> Result<Node, ParseError> {
        if depth > MAX_DEPTH {
            return Err(self.error(format!("values nested deeper than {MAX_DEPTH} levels")));
        }
        self.skip_trivia()?;
        let pos = self.pos();
        let c = self
            .peek()
            .ok_or_else(|| self.error("expected a value, found the end of the file"))?;
        let kind = match c {
            '[' => {
                self.bump();
                Kind::List(self.sequence(']', depth)?)
            }
            '{' => {
                self.bump();
                Kind::Map(self.map(depth)?)
            }
            '(' => self.parenthesized(None, depth)?,
            '"' => Kind::Str(self.string()?),
            '\'' => Kind::Char(self.char_literal()?),
            'r' if matches!(self.peek_at(1), Some('"' | '#')) => Kind::Str(self.raw_string()?),
            c if c.is_ascii_digit() || c == '-' || c == '+' || c == '.' => self.number()?,
            c if c.is_alphabetic() || c == '_' => {
                let name = self.ident();
                match name.as_str() {
                    "true" => Kind::Bool(true),
                    "false" => Kind::Bool(false),
                    "inf" => Kind::Float(f64::INFINITY),
                    "NaN" => Kind::Float(f64::NAN),
                    "None" => Kind::None,
                    "Some" => {
                        self.expect('(')?;
                        let inner = self.value(depth + 1)?;
                        self.skip_trivia()?;
                        if self.peek() == Some(',') {
                            self.bump();
                        }
                        self.expect(')')?;
                        Kind::Some(Box::new(inner))
                    }
                    _ => {
                        self.skip_trivia()?;
                        if self.peek() == Some('(') {
                            self.parenthesized(Some(name), depth)?
                        } else {
                            Kind::Ident(name)
                        }
                    }
                }
            }
            other => return Err(self.error(format!("unexpected character '{other}'"))),
        };
        Ok(Node { pos, kind })
    }

    fn ident(&mut self) -> String {
        let mut s = String::new();
        while let Some(c) = self.peek() {
            if c.is_alphanumeric() || c == '_' {
                s.push(c);
                self.bump();
            } else {
                break;
            }
        }
        s
    }

    fn sequence(&mut self, close: char, depth: usize) -> Result<Vec<Node>, ParseError> {
        let mut items = Vec::new();
        loop {
            self.skip_trivia()?;
            if self.peek() == Some(close) {
                self.bump();
                return Ok(items);
            }
            items.push(self.value(depth + 1)?);
            self.skip_trivia()?;
            match self.peek() {
                Some(',') => {
                    self.bump();
                }
                Some(c) if c == close => {}
                Some(c) => {
                    return Err(self.error(format!("expected ',' or '{close}', found '{c}'")));
                }
                None => {
                    return Err(
                        self.error(format!("expected '{close}', found the end of the file"))
                    );
                }
            }
        }
    }

    fn map(&mut self, depth: usize) -> Result<Vec<(Node, Node)>, ParseError> {
        let mut entries = Vec::new();
        loop {
            self.skip_trivia()?;
            if self.peek() == Some('}') {
                self.bump();
                return Ok(entries);
            }
            let key = self.value(depth + 1)?;
            self.expect(':')?;
            let value = self.value(depth + 1)?;
            entries.push((key, value));
            self.skip_trivia()?;
            match self.peek() {
                Some(',') => {
                    self.bump();
                }
                Some('}') => {}
                Some(c) => return Err(self.error(format!("expected ',' or '}}', found '{c}'"))),
                None => return Err(self.error("expected '}', found the end of the file")),
            }
        }
    }

    /// After a `(` (possibly preceded by a name): unit, struct or tuple.
    fn parenthesized(&mut self, name: Option<String>, depth: usize) -> Result<Kind, ParseError> {
        self.expect('(')?;
        self.skip_trivia()?;
        if self.peek() == Some(')') {
            self.bump();
            return Ok(match name {
                Some(n) => Kind::Tuple(Some(n), Vec::new()),
                None => Kind::Unit,
            });
        }
        if self.looks_like_field() {
            let mut fields = Vec::new();
            loop {
                self.skip_trivia()?;
                if self.peek() == Some(')') {
                    self.bump();
                    return Ok(Kind::Struct(name, fields));
                }
                let pos = self.pos();
                if !self.peek().is_some_and(|c| c.is_alphabetic() || c == '_') {
                    return Err(self.error("expected a field name"));
                }
                let field = Field {
                    name: self.ident(),
                    pos,
                };
                self.expect(':')?;
                let value = self.value(depth + 1)?;
                fields.push((field, value));
                self.skip_trivia()?;
                match self.peek() {
                    Some(',') => {
                        self.bump();
                    }
                    Some(')') => {}
                    Some(c) => return Err(self.error(format!("expected ',' or ')', found '{c}'"))),
                    None => return Err(self.error("expected ')', found the end of the file")),
                }
            }
        }
        Ok(Kind::Tuple(name, self.sequence(')', depth)?))
    }

    /// True when the next tokens are `identifier :` (but not `::`).
    fn looks_like_field(&self) -> bool {
        let mut chars = self.rest().chars().peekable();
        if !chars.peek().is_some_and(|c| c.is_alphabetic() || *c == '_') {
            return false;
        }
        while chars
            .next_if(|c| c.is_alphanumeric() || *c == '_')
            .is_some()
        {}
        while chars.next_if(|c| c.is_whitespace()).is_some() {}
        chars.next() == Some(':') && chars.next() != Some(':')
    }

    fn number(&mut self) -> Result<Kind, ParseError> {
        let start = self.pos();
        let mut text = String::new();
        if let Some(sign @ ('-' | '+')) = self.peek() {
            text.push(sign);
            self.bump();
        }
        if self.peek().is_some_and(|c| c.is_alphabetic()) {
            let word = self.ident();
            let x = match word.as_str() {
                "inf" => f64::INFINITY,
                "NaN" => f64::NAN,
                _ => {
                    return Err(ParseError {
                        pos: start,
                        message: format!("invalid number '{text}{word}'"),
                    });
                }
            };
            return Ok(Kind::Float(if text == "-" { -x } else { x }));
        }
        while let Some(c) = self.peek() {
            let exponent_sign =
                matches!(c, '+' | '-') && matches!(text.chars().last(), Some('e' | 'E'));
            if c.is_ascii_alphanumeric() || c == '_' || c == '.' || exponent_sign {
                if c != '_' {
                    text.push(c);
                }
                self.bump();
            } else {
                break;
            }
        }
        let bad = || ParseError {
            pos: start,
            message: format!("invalid number '{text}'"),
        };
        let (sign, digits) = match text.strip_prefix('-') {
            Some(rest) => (-1i64, rest),
            None => (1, text.trim_start_matches('+')),
        };
        for (prefix, radix) in [("0x", 16), ("0b", 2), ("0o", 8)] {
            if let Some(body) = digits.strip_prefix(prefix) {
                return i64::from_str_radix(body, radix)
                    .map(|v| Kind::Int(sign * v))
                    .map_err(|_| bad());
            }
        }
        if digits.is_empty() || !digits.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
            return Err(bad());
        }
        if digits.contains(['.', 'e', 'E']) {
            text.parse::<f64>().map(Kind::Float).map_err(|_| bad())
        } else {
            match text.parse::<i64>() {
                Ok(i) => Ok(Kind::Int(i)),
                Err(_) if digits.chars().all(|c| c.is_ascii_digit()) => Err(ParseError {
                    pos: start,
                    message: format!("integer '{text}' is out of range"),
                }),
                Err(_) => Err(bad()),
            }
        }
    }

    fn escape(&mut self) -> Result<char, ParseError> {
        let pos = self.pos();
        let c = self
            .bump()
            .ok_or_else(|| self.error("unterminated escape"))?;
        Ok(match c {
            'n' => '\n',
            'r' => '\r',
            't' => '\t',
            '0' => '\0',
            '\\' => '\\',
            '"' => '"',
            '\'' => '\'',
            'x' => {
                let hex: String = [self.bump(), self.bump()].iter().flatten().collect();
                u8::from_str_radix(&hex, 16)
                    .ok()
                    .filter(|b| b.is_ascii())
                    .map(char::from)
                    .ok_or(ParseError {
                        pos,
                        message: format!("invalid escape '\\x{hex}'"),
                    })?
            }
            'u' => {
                self.expect('{')?;
                let mut hex = String::new();
                while let Some(c) = self.peek() {
                    if c == '}' {
                        break;
                    }
                    hex.push(c);
                    self.bump();
                }
                self.expect('}')?;
                u32::from_str_radix(&hex, 16)
                    .ok()
                    .and_then(char::from_u32)
                    .ok_or(ParseError {
                        pos,
                        message: format!("invalid escape '\\u{{{hex}}}'"),
                    })?
            }
            other => {
                return Err(ParseError {
                    pos,
                    message: format!("unknown escape '\\{other}'"),
                });
            }
        })
    }

    fn string(&mut self) -> Result<String, ParseError> {
        let start = self.pos();
        self.bump();
        let mut s = String::new();
        loop {
            match self.bump() {
                Some('"') => return Ok(s),
                Some('\\') => s.push(self.escape()?),
                Some(c) => s.push(c),
                None => {
                    return Err(ParseError {
                        pos: start,
                        message: "unterminated string".into(),
                    });
                }
            }
        }
    }

    fn raw_string(&mut self) -> Result<String, ParseError> {
        let start = self.pos();
        self.bump();
        let mut hashes = 0;
        while self.peek() == Some('#') {
            self.bump();
            hashes += 1;
        }
        if self.bump() != Some('"') {
            return Err(ParseError {
                pos: start,
                message: "invalid raw string".into(),
            });
        }
        let mut s = String::new();
        loop {
            match self.bump() {
                Some('"') if (0..hashes).all(|k| self.peek_at(k) == Some('#')) => {
                    for _ in 0..hashes {
                        self.bump();
                    }
                    return Ok(s);
                }
                Some(c) => s.push(c),
                None => {
                    return Err(ParseError {
                        pos: start,
                        message: "unterminated raw string".into(),
                    });
                }
            }
        }
    }

    fn char_literal(&mut self) -> Result<char, ParseError> {
        let start = self.pos();
        self.bump();
        let c = match self.bump() {
            Some('\\') => self.escape()?,
            Some(c) => c,
            None => {
                return Err(ParseError {
                    pos: start,
                    message: "unterminated character".into(),
                });
            }
        };
        if self.bump() != Some('\'') {
            return Err(ParseError {
                pos: start,
                message: "unterminated character".into(),
            });
        }
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_structs_maps_lists_and_positions() {
        let text = "// header\n(\n    version: 1,\n    nodes: { \"a\": (type: \"x\", position: (1.5, -2)) },\n    edges: [\"a.b -> c.d\"],\n)";
        let root = parse(text).unwrap();
        let fields = root.fields().unwrap();
        assert_eq!(fields[0].0.name, "version");
        assert_eq!(fields[0].0.pos, Pos { line: 3, col: 5 });
        assert_eq!(fields[0].1.kind, Kind::Int(1));
        let Kind::Map(entries) = &fields[1].1.kind else {
            panic!("map")
        };
        assert_eq!(entries[0].0.as_str(), Some("a"));
        assert_eq!(entries[0].0.pos, Pos { line: 4, col: 14 });
        let node = entries[0].1.fields().unwrap();
        assert_eq!(node[1].1.items().unwrap()[1].as_f64(), Some(-2.0));
    }

    #[test]
    fn numbers_strings_and_specials() {
        let v = parse("[1e3, -0.5, 0x1F, inf, -inf, NaN, 1_000, r#\"a\"b\"#, \"\\u{e9}\\n\", 'c', None, Some(2), Foo, ()]").unwrap();
        let items = v.items().unwrap();
        assert_eq!(items[0].kind, Kind::Float(1000.0));
        assert_eq!(items[1].kind, Kind::Float(-0.5));
        assert_eq!(items[2].kind, Kind::Int(31));
        assert_eq!(items[3].kind, Kind::Float(f64::INFINITY));
        assert_eq!(items[4].kind, Kind::Float(f64::NEG_INFINITY));
        assert!(matches!(items[5].kind, Kind::Float(x) if x.is_nan()));
        assert_eq!(items[6].kind, Kind::Int(1000));
        assert_eq!(items[7].kind, Kind::Str("a\"b".into()));
        assert_eq!(items[8].kind, Kind::Str("é\n".into()));
        assert_eq!(items[9].kind, Kind::Char('c'));
        assert_eq!(items[10].kind, Kind::None);
        assert!(matches!(&items[11].kind, Kind::Some(b) if b.kind == Kind::Int(2)));
        assert_eq!(items[12].kind, Kind::Ident("Foo".into()));
        assert_eq!(items[13].kind, Kind::Unit);
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        // The parser reads the text in place, by byte offset; positions still count characters.
        let v = parse("(é_ü: \"ñandú 😀\", b: 'ß', c: [1, 2])").unwrap();
        let fields = v.fields().unwrap();
        assert_eq!(fields[0].0.name, "é_ü");
        assert_eq!(fields[0].1.kind, Kind::Str("ñandú 😀".into()));
        assert_eq!(fields[1].0.pos, Pos { line: 1, col: 18 });
        assert_eq!(fields[1].1.kind, Kind::Char('ß'));
        assert_eq!(fields[2].1.pos, Pos { line: 1, col: 29 });
        let e = parse("[\"😀é\", @]").unwrap_err();
        assert_eq!(e.pos, Pos { line: 1, col: 8 });
        // `a::b` is not a field.
        assert!(parse("(a::b)").is_err());
    }

    #[test]
    fn errors_have_positions() {
        let e = parse("(\n  a: [1, 2\n").unwrap_err();
        assert_eq!(e.pos.line, 3);
        assert!(e.message.contains("expected ']'"), "{}", e.message);
        let e = parse("(a: \"open)").unwrap_err();
        assert_eq!(e.pos, Pos { line: 1, col: 5 });
        assert!(parse("(a: 1) extra").is_err());
        assert!(
            parse(&"[".repeat(1000))
                .unwrap_err()
                .message
                .contains("nested")
        );
        assert!(
            parse("99999999999999999999")
                .unwrap_err()
                .message
                .contains("out of range")
        );
    }
}
