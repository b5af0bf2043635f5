//! Arithmetic expressions over x, y and z (`math.expression`): a small recursive-descent parser that
//! compiles the text once into postfix instructions, and a stack evaluator over `f64`. Flat sums
//! and products are loops in the parser and runs of instructions in the program, so a sum of a
//! million terms parses, evaluates and drops without recursion; nesting (parentheses, signs,
//! powers, calls) is what recurses, and it stops at 200 levels with an error.
//!
//! Hand-written rather than `evalexpr`: evalexpr reads `1/2` as integer division (0) and its errors
//! carry no position, while a designer needs real-number arithmetic and an error that points at the
//! column. The grammar (lowest precedence first):
//!
//! ```text
//! sum     := product (('+' | '-') product)*
//! product := unary (('*' | '/') unary)*
//! unary   := ('-' | '+') unary | power
//! power   := atom ('^' unary)?          right-associative: 2^3^2 = 2^9; -2^2 = -4
//! atom    := number | name | name '(' sum (',' sum)* ')' | '(' sum ')'
//! ```

use std::fmt;

/// Functions an expression may call, with their argument counts (`None`: two or more).
const FUNCTIONS: &[(&str, Option<usize>)] = &[
    ("sin", Some(1)),
    ("cos", Some(1)),
    ("tan", Some(1)),
    ("asin", Some(1)),
    ("acos", Some(1)),
    ("atan", Some(1)),
    ("atan2", Some(2)),
    ("sqrt", Some(1)),
    ("abs", Some(1)),
    ("exp", Some(1)),
    ("ln", Some(1)),
    ("log10", Some(1)),
    ("floor", Some(1)),
    ("ceil", Some(1)),
    ("round", Some(1)),
    ("min", None),
    ("max", None),
];

/// The variables an expression may name.
pub const VARIABLES: [&str; 3] = ["x", "y", "z"];

/// A parse or evaluation error; `column` is 1-based, in characters.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message} (column {column})")]
pub struct ExpressionError {
    /// What is wrong.
    pub message: String,
    /// Where, counted in characters from 1.
    pub column: usize,
}

/// A parsed expression: postfix instructions and the stack they need.
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    code: Vec<Instr>,
    stack: usize,
}

/// One postfix instruction.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Instr {
    /// Push a number literal or a constant.
    Number(f64),
    /// Push x (0), y (1) or z (2).
    Variable(usize),
    /// Negate the top.
    Negate,
    /// Pop b, pop a, push a op b.
    Binary(Op),
    /// Pop the arguments, push the function's value: index into the function table, argument
    /// count.
    Call(usize, usize),
}

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// +
    Add,
    /// −
    Subtract,
    /// ×
    Multiply,
    /// ÷
    Divide,
    /// ^
    Power,
}

impl fmt::Display for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Op::Add => "+",
            Op::Subtract => "-",
            Op::Multiply => "*",
            Op::Divide => "/",
            Op::Power => "^",
        })
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Number(f64),
    Name(String),
    Op(Op),
    Open,
    Close,
    Comma,
    End,
}

impl fmt::Display for Token {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Number(x) => write!(f, "the number {x}"),
            Token::Name(n) => write!(f, "'{n}'"),
            Token::Op(op) => write!(f, "'{op}'"),
            Token::Open => f.write_str("'('"),
            Token::Close => f.write_str("')'"),
            Token::Comma => f.write_str("','"),
            Token::End => f.write_str("the end"),
        }
    }
}

fn error(message: impl Into<String>, column: usize) -> ExpressionError {
    ExpressionError {
        message: message.into(),
        column,
    }
}

/// Splits the text into tokens with their 1-based columns.
fn tokenize(text: &str) -> Result<Vec<(Token, usize)>, ExpressionError> {
    let chars: Vec<char> = text.chars().collect();
    let mut tokens = Vec::new();
    let mut k = 0;
    while k < chars.len() {
        let c = chars[k];
        let column = k + 1;
        if c.is_whitespace() {
            k += 1;
            continue;
        }
        let simple = match c {
            '+' => Some(Token::Op(Op::Add)),
            '-' | '−' => Some(Token::Op(Op::Subtract)),
            '*' | '×' => Some(Token::Op(Op::Multiply)),
            '/' | '÷' => Some(Token::Op(Op::Divide)),
            '^' => Some(Token::Op(Op::Power)),
            '(' => Some(Token::Open),
            ')' => Some(Token::Close),
            ',' => Some(Token::Comma),
            _ => None,
        };
        if let Some(token) = simple {
            tokens.push((token, column));
            k += 1;
        } else if c.is_ascii_digit() || c == '.' {
            let start = k;
            while k < chars.len() && (chars[k].is_ascii_digit() || chars[k] == '.') {
                k += 1;
            }
            // An exponent only when digits follow (`2e` is 2 followed by the constant e).
            if k < chars.len() && matches!(chars[k], 'e' | 'E') {
                let mut j = k + 1;
                if j < chars.len() && matches!(chars[j], '+' | '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    k = j;
                    while k < chars.len() && chars[k].is_ascii_digit() {
                        k += 1;
                    }
                }
            }
            let literal: String = chars[start..k].iter().collect();
            let value: f64 = literal
                .parse()
                .map_err(|_| error(format!("'{literal}' is not a number"), column))?;
            tokens.push((Token::Number(value), column));
        } else if c.is_alphabetic() || c == '_' {
            let start = k;
            while k < chars.len() && (chars[k].is_alphanumeric() || chars[k] == '_') {
                k += 1;
            }
            tokens.push((Token::Name(chars[start..k].iter().collect()), column));
        } else {
            return Err(error(format!("unexpected character '{c}'"), column));
        }
    }
    tokens.push((Token::End, chars.len() + 1));
    Ok(tokens)
}

/// Deepest nesting of parentheses and unary signs accepted (keeps the parser's recursion bounded).
const MAX_DEPTH: usize = 200;

struct Parser {
    tokens: Vec<(Token, usize)>,
    at: usize,
    depth: usize,
    /// The program compiled so far.
    code: Vec<Instr>,
}

impl Parser {
    fn peek(&self) -> &Token {
        &self.tokens[self.at].0
    }

    fn column(&self) -> usize {
        self.tokens[self.at].1
    }

    fn next(&mut self) -> (Token, usize) {
        let t = self.tokens[self.at].clone();
        if self.at + 1 < self.tokens.len() {
            self.at += 1;
        }
        t
    }

    fn deeper(&mut self) -> Result<(), ExpressionError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(error(
                format!("the expression nests deeper than {MAX_DEPTH} levels"),
                self.column(),
            ));
        }
        Ok(())
    }

    fn sum(&mut self) -> Result<(), ExpressionError> {
        self.product()?;
        while let Token::Op(op @ (Op::Add | Op::Subtract)) = *self.peek() {
            self.next();
            self.product()?;
            self.code.push(Instr::Binary(op));
        }
        Ok(())
    }

    fn product(&mut self) -> Result<(), ExpressionError> {
        self.unary()?;
        while let Token::Op(op @ (Op::Multiply | Op::Divide)) = *self.peek() {
            self.next();
            self.unary()?;
            self.code.push(Instr::Binary(op));
        }
        Ok(())
    }

    fn unary(&mut self) -> Result<(), ExpressionError> {
        match self.peek() {
            Token::Op(op @ (Op::Subtract | Op::Add)) => {
                let negate = *op == Op::Subtract;
                self.next();
                self.deeper()?;
                self.unary()?;
                self.depth -= 1;
                if negate {
                    self.code.push(Instr::Negate);
                }
                Ok(())
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<(), ExpressionError> {
        self.atom()?;
        if *self.peek() == Token::Op(Op::Power) {
            self.next();
            self.deeper()?;
            self.unary()?;
            self.depth -= 1;
            self.code.push(Instr::Binary(Op::Power));
        }
        Ok(())
    }

    fn expect_close(&mut self, opened_at: usize) -> Result<(), ExpressionError> {
        match self.next() {
            (Token::Close, _) => Ok(()),
            (other, column) => Err(error(
                format!("expected ')' to close the '(' of column {opened_at}, found {other}"),
                column,
            )),
        }
    }

    fn atom(&mut self) -> Result<(), ExpressionError> {
        let (token, column) = self.next();
        match token {
            Token::Number(x) => {
                self.code.push(Instr::Number(x));
                Ok(())
            }
            Token::Open => {
                self.deeper()?;
                self.sum()?;
                self.depth -= 1;
                self.expect_close(column)
            }
            Token::Name(name) if *self.peek() == Token::Open => self.call(name, column),
            Token::Name(name) => {
                let value = name_value(&name, column)?;
                self.code.push(value);
                Ok(())
            }
            other => Err(error(
                format!("expected a number, a name or '(', found {other}"),
                column,
            )),
        }
    }

    fn call(&mut self, name: String, column: usize) -> Result<(), ExpressionError> {
        let Some(index) = FUNCTIONS.iter().position(|(n, _)| *n == name) else {
            return Err(error(
                format!(
                    "unknown function '{}' (known: {})",
                    excerpt(&name),
                    FUNCTIONS
                        .iter()
                        .map(|(n, _)| *n)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                column,
            ));
        };
        let (_, open) = self.next();
        self.deeper()?;
        self.sum()?;
        let mut args = 1;
        while *self.peek() == Token::Comma {
            self.next();
            self.sum()?;
            args += 1;
        }
        self.depth -= 1;
        self.expect_close(open)?;
        let count_ok = match FUNCTIONS[index].1 {
            Some(n) => args == n,
            None => args >= 2,
        };
        if !count_ok {
            let wanted = match FUNCTIONS[index].1 {
                Some(1) => "1 argument".to_string(),
                Some(n) => format!("{n} arguments"),
                None => "2 or more arguments".to_string(),
            };
            return Err(error(format!("{name} takes {wanted}, got {args}"), column));
        }
        self.code.push(Instr::Call(index, args));
        Ok(())
    }
}

/// A name as an error message quotes it: at most 40 characters.
fn excerpt(name: &str) -> String {
    cnets_engine::files::excerpt(name, 40)
}

fn name_value(name: &str, column: usize) -> Result<Instr, ExpressionError> {
    if let Some(k) = VARIABLES.iter().position(|v| *v == name) {
        return Ok(Instr::Variable(k));
    }
    match name {
        "pi" => Ok(Instr::Number(std::f64::consts::PI)),
        "e" => Ok(Instr::Number(std::f64::consts::E)),
        _ if FUNCTIONS.iter().any(|(n, _)| *n == name) => Err(error(
            format!("'{name}' is a function: call it with parentheses, e.g. {name}(x)"),
            column,
        )),
        _ => Err(error(
            format!("unknown name '{}' (known: x, y, z, pi, e)", excerpt(name)),
            column,
        )),
    }
}

/// Parses an expression into its program.
pub fn parse(text: &str) -> Result<Expr, ExpressionError> {
    let tokens = tokenize(text)?;
    let mut parser = Parser {
        tokens,
        at: 0,
        depth: 0,
        code: Vec::new(),
    };
    if *parser.peek() == Token::End {
        return Err(error("the expression is empty", 1));
    }
    parser.sum()?;
    match parser.next() {
        (Token::End, _) => {}
        (Token::Close, column) => return Err(error("')' without a matching '('", column)),
        (other, column) => {
            return Err(error(
                format!("expected an operator or the end, found {other}"),
                column,
            ));
        }
    }
    // The deepest the stack gets (a parsed program is balanced: one value at the end).
    let (mut height, mut stack) = (0usize, 0usize);
    for instr in &parser.code {
        height = match *instr {
            Instr::Number(_) | Instr::Variable(_) => height + 1,
            Instr::Negate => height,
            Instr::Binary(_) => height - 1,
            Instr::Call(_, n) => height + 1 - n,
        };
        stack = stack.max(height);
    }
    Ok(Expr {
        code: parser.code,
        stack,
    })
}

impl Expr {
    /// The value for the given x, y and z (radians for the trigonometric functions). May be NaN or
    /// infinite (the node checks).
    pub fn eval(&self, vars: &[f64; 3]) -> f64 {
        let mut stack: Vec<f64> = Vec::with_capacity(self.stack);
        for instr in &self.code {
            match *instr {
                Instr::Number(x) => stack.push(x),
                Instr::Variable(k) => stack.push(vars[k]),
                Instr::Negate => {
                    if let Some(top) = stack.last_mut() {
                        *top = -*top;
                    }
                }
                Instr::Binary(op) => {
                    let b = stack.pop().unwrap_or(f64::NAN);
                    let a = stack.pop().unwrap_or(f64::NAN);
                    stack.push(match op {
                        Op::Add => a + b,
                        Op::Subtract => a - b,
                        Op::Multiply => a * b,
                        Op::Divide => a / b,
                        Op::Power => a.powf(b),
                    });
                }
                Instr::Call(index, n) => {
                    let start = stack.len().saturating_sub(n);
                    let value = call(index, &stack[start..]);
                    stack.truncate(start);
                    stack.push(value);
                }
            }
        }
        stack.pop().unwrap_or(f64::NAN)
    }
}

/// Function `index` of the table on its arguments.
fn call(index: usize, args: &[f64]) -> f64 {
    let a = args.first().copied().unwrap_or(f64::NAN);
    match FUNCTIONS[index].0 {
        "sin" => a.sin(),
        "cos" => a.cos(),
        "tan" => a.tan(),
        "asin" => a.asin(),
        "acos" => a.acos(),
        "atan" => a.atan(),
        "atan2" => a.atan2(args.get(1).copied().unwrap_or(f64::NAN)),
        "sqrt" => a.sqrt(),
        "abs" => a.abs(),
        "exp" => a.exp(),
        "ln" => a.ln(),
        "log10" => a.log10(),
        "floor" => a.floor(),
        "ceil" => a.ceil(),
        "round" => a.round(),
        "min" => args.iter().copied().fold(a, f64::min),
        "max" => args.iter().copied().fold(a, f64::max),
        _ => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str, x: f64, y: f64) -> f64 {
        parse(text).unwrap().eval(&[x, y, 0.0])
    }

    #[test]
    fn precedence_and_associativity_follow_mathematics() {
        assert_eq!(value("1 + 2 * 3", 0.0, 0.0), 7.0);
        assert_eq!(value("(1 + 2) * 3", 0.0, 0.0), 9.0);
        assert_eq!(value("2^3^2", 0.0, 0.0), 512.0);
        assert_eq!(value("-2^2", 0.0, 0.0), -4.0);
        assert_eq!(value("2^-1", 0.0, 0.0), 0.5);
        assert_eq!(value("8 / 2 / 2", 0.0, 0.0), 2.0);
        assert_eq!(value("1/2", 0.0, 0.0), 0.5, "real division, not integer");
        assert_eq!(value("10 - 4 - 3", 0.0, 0.0), 3.0);
        assert_eq!(value("1.5e3 + 2E-1", 0.0, 0.0), 1500.2);
        assert_eq!(value("2*e", 0.0, 0.0), 2.0 * std::f64::consts::E);
        assert_eq!(value("--x", 4.0, 0.0), 4.0);
    }

    #[test]
    fn functions_and_constants() {
        let v = value("sin(pi*x)^2 + y/4", 0.5, 2.0);
        assert!((v - 1.5).abs() < 1e-15, "{v}");
        assert_eq!(value("atan2(y, x)", 1.0, 1.0), std::f64::consts::FRAC_PI_4);
        assert_eq!(value("min(x, y, 3)", 5.0, 4.0), 3.0);
        assert_eq!(value("max(x, y)", 5.0, 4.0), 5.0);
        assert_eq!(value("round(2.5) + floor(-0.5) + ceil(0.2)", 0.0, 0.0), 3.0);
        assert!((value("log10(1000) + ln(e)", 0.0, 0.0) - 4.0).abs() < 1e-15);
        assert_eq!(value("sqrt(abs(-16))", 0.0, 0.0), 4.0);
    }

    #[test]
    fn errors_name_the_column_and_the_name() {
        let e = parse("1 + * 2").unwrap_err();
        assert_eq!(e.column, 5, "{e}");
        let e = parse("sin(x").unwrap_err();
        assert_eq!(e.column, 6, "{e}");
        assert!(e.message.contains("column 4"), "{e}");
        let e = parse("2 * foo").unwrap_err();
        assert_eq!(e.column, 5);
        assert!(e.message.contains("'foo'"), "{e}");
        let e = parse("sinh(x)").unwrap_err();
        assert!(e.message.contains("unknown function 'sinh'"), "{e}");
        let e = parse("atan2(x)").unwrap_err();
        assert!(e.message.contains("2 arguments, got 1"), "{e}");
        let e = parse("x )").unwrap_err();
        assert_eq!(e.column, 3);
        assert_eq!(parse("  ").unwrap_err().column, 1);
        let e = parse("2 # 3").unwrap_err();
        assert_eq!(e.column, 3);
        assert!(e.to_string().ends_with("(column 3)"), "{e}");
        assert!(parse("sin").unwrap_err().message.contains("function"));
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        let deep = format!("{}x{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(parse(&deep).unwrap_err().message.contains("nests deeper"));
        let signs = format!("{}x", "-".repeat(100_000));
        assert!(parse(&signs).is_err());
        let powers = vec!["2"; 100_000].join("^");
        assert!(parse(&powers).is_err());
    }

    #[test]
    fn long_flat_sums_and_products_evaluate_without_recursion() {
        // 150 000 terms (the issue's): parsed, evaluated and dropped on a small thread stack.
        let sum = vec!["x"; 150_000].join(" + ");
        let product = vec!["1"; 150_000].join(" * ");
        let handle = std::thread::Builder::new()
            .stack_size(256 * 1024)
            .spawn(move || {
                let s = parse(&sum).unwrap().eval(&[2.0, 0.0, 0.0]);
                let p = parse(&product).unwrap().eval(&[0.0; 3]);
                (s, p)
            })
            .unwrap();
        assert_eq!(handle.join().unwrap(), (300_000.0, 1.0));
        // A name of a million characters is quoted short.
        let e = parse(&"q".repeat(1_000_000)).unwrap_err();
        assert!(e.message.len() < 100, "{}", e.message.len());
    }
}
