//! Why a list's table refused a value, a cell's text or a paste. Shown in the table window's
//! note, naming the cell or the line and field of the pasted text.

use thiserror::Error;

use super::summary::count;

/// What a cell's text should have been.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expected {
    /// A number (`.` as the decimal point).
    Number,
    /// A whole number.
    WholeNumber,
    /// `true` or `false`.
    Boolean,
}

impl std::fmt::Display for Expected {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Expected::Number => "a number",
            Expected::WholeNumber => "a whole number",
            Expected::Boolean => "true or false",
        })
    }
}

/// Why one cell's text was not read.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum CellError {
    /// Nothing was written.
    #[error("empty: expected {0}")]
    Empty(Expected),
    /// A number written with a decimal comma.
    #[error("'{text}' is not a number: use '.' as the decimal point")]
    DecimalComma {
        /// The text, trimmed.
        text: String,
    },
    /// The text is not of the cell's kind.
    #[error("'{text}' is not {expected}")]
    Not {
        /// The text, trimmed.
        text: String,
        /// What the cell takes.
        expected: Expected,
    },
    /// The row has fewer cells.
    #[error("there is no column {0} in this row")]
    NoColumn(usize),
}

/// Why a value cannot be edited as a table.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum NotATable {
    /// One value, not a list.
    #[error("a single {0} is not a list")]
    Single(String),
    /// An item of the list is neither a cell, a point nor a list of cells.
    #[error("item {item}: it is a {type_name}")]
    Item {
        /// The item's index.
        item: usize,
        /// Its type.
        type_name: String,
    },
    /// An item's own item is not a cell.
    #[error("item {item}: its item {inner} is a {type_name}")]
    Inner {
        /// The item's index.
        item: usize,
        /// The index inside it.
        inner: usize,
        /// That value's type.
        type_name: String,
    },
}

/// Why an edit of the table (a cell typed, a paste) was refused; nothing changed.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum TableEditError {
    /// The cell's row was removed meanwhile.
    #[error("{cell}: there is no row {row} any more")]
    RowGone {
        /// The cell's name (`row 2, column 1`).
        cell: String,
        /// The row.
        row: usize,
    },
    /// The typed text was not of the cell's kind.
    #[error("{cell}: {error}")]
    Cell {
        /// The cell's name.
        cell: String,
        /// Why.
        error: CellError,
    },
    /// The pasted text has no lines.
    #[error("nothing to paste: the text has no lines")]
    NothingToPaste,
    /// A pasted line is wider than the row it lands on.
    #[error(
        "line {line}: {} from column {column} do not fit in row {row}, which has {}; nothing \
         was pasted",
        count(*.fields, ("field", "fields")),
        count(*.width, ("column", "columns"))
    )]
    DoesNotFit {
        /// The line of the text (from 1).
        line: usize,
        /// Its fields.
        fields: usize,
        /// The column pasted at, named.
        column: String,
        /// The row it lands on.
        row: usize,
        /// That row's cells.
        width: usize,
    },
    /// A pasted field was not of its cell's kind.
    #[error("line {line}, field {field}: {error}; nothing was pasted")]
    Field {
        /// The line of the text (from 1).
        line: usize,
        /// The field of the line (from 1).
        field: usize,
        /// Why.
        error: CellError,
    },
    /// A pasted line for a point has not 3 fields.
    #[error(
        "line {line}: {}, but points need 3 (x, y, z); nothing was pasted",
        count(*.fields, ("field", "fields"))
    )]
    NotAPoint {
        /// The line of the text (from 1).
        line: usize,
        /// Its fields.
        fields: usize,
    },
    /// A pasted line of several fields for a list of one column.
    #[error("line {line}: {fields} fields, but this list has one column; nothing was pasted")]
    OneColumn {
        /// The line of the text (from 1).
        line: usize,
        /// Its fields.
        fields: usize,
    },
}
