//! The list editor's model: a literal list (or polyline) seen as rows of cells, and the edits of
//! the table — a cell, add a row, remove rows, paste — made so that nothing the designer did not
//! touch changes: the value keeps its nesting, every item its kind (a point stays a point, an
//! integer an integer), the list its length unless rows were added or removed, and every untouched
//! number its bits.
//!
//! A row is one item of the list: a single value (a list of numbers is one column), a point or
//! vector (x, y, z), or a list of single values (a row of a table; rows may differ in length).

use std::collections::BTreeSet;
use std::sync::Arc;

use cnets_engine::{Value, ValueType};
use cnets_geometry::{DVec3, Polyline};

use super::errors::{CellError, NotATable, TableEditError};
use super::summary::count;
use super::tsv;

/// One cell: a single value.
#[derive(Clone, Debug)]
pub enum Cell {
    /// An empty item (`None` in the file).
    Null,
    /// A number.
    Number(f64),
    /// A whole number.
    Integer(i64),
    /// A truth value.
    Boolean(bool),
    /// A text.
    Text(Arc<str>),
}

impl Cell {
    fn of(v: &Value) -> Option<Cell> {
        Some(match v {
            Value::Null => Cell::Null,
            Value::Number(x) => Cell::Number(*x),
            Value::Integer(i) => Cell::Integer(*i),
            Value::Boolean(b) => Cell::Boolean(*b),
            Value::Text(t) => Cell::Text(t.clone()),
            _ => return None,
        })
    }

    fn value(&self) -> Value {
        match self {
            Cell::Null => Value::Null,
            Cell::Number(x) => Value::Number(*x),
            Cell::Integer(i) => Value::Integer(*i),
            Cell::Boolean(b) => Value::Boolean(*b),
            Cell::Text(t) => Value::Text(t.clone()),
        }
    }

    /// The cell's text: numbers in full ([`tsv::format_number`]), an empty item as nothing.
    pub fn text(&self) -> String {
        match self {
            Cell::Null => String::new(),
            Cell::Number(x) => tsv::format_number(*x),
            Cell::Integer(i) => i.to_string(),
            Cell::Boolean(b) => b.to_string(),
            Cell::Text(t) => t.to_string(),
        }
    }

    /// A cell of the same kind read from `text` (an empty item takes a number).
    fn parse_like(&self, text: &str) -> Result<Cell, CellError> {
        Ok(match self {
            Cell::Null if text.trim().is_empty() => Cell::Null,
            Cell::Null | Cell::Number(_) => Cell::Number(tsv::parse_number(text)?),
            Cell::Integer(_) => Cell::Integer(tsv::parse_integer(text)?),
            Cell::Boolean(_) => Cell::Boolean(tsv::parse_boolean(text)?),
            Cell::Text(_) => Cell::Text(Arc::from(text)),
        })
    }

    fn kind_name(&self) -> &'static str {
        match self {
            Cell::Null => "none",
            Cell::Number(_) => "number",
            Cell::Integer(_) => "integer",
            Cell::Boolean(_) => "boolean",
            Cell::Text(_) => "text",
        }
    }
}

/// One row: one item of the list.
#[derive(Clone, Debug)]
pub enum Row {
    /// A single value (one cell).
    Scalar(Cell),
    /// A point or a vector: x, y, z.
    Triple {
        /// The coordinates.
        xyz: [f64; 3],
        /// A vector rather than a point.
        vector: bool,
    },
    /// A list of single values (a row of a table).
    List(Vec<Cell>),
}

impl Row {
    /// The row of item `item` of a list, `v`.
    fn of(item: usize, v: &Value) -> Result<Row, NotATable> {
        if let Some(cell) = Cell::of(v) {
            return Ok(Row::Scalar(cell));
        }
        match v {
            Value::Point(p) => Ok(Row::Triple {
                xyz: p.to_array(),
                vector: false,
            }),
            Value::Vector(p) => Ok(Row::Triple {
                xyz: p.to_array(),
                vector: true,
            }),
            Value::List(items) => items
                .iter()
                .enumerate()
                .map(|(inner, value)| {
                    Cell::of(value).ok_or_else(|| NotATable::Inner {
                        item,
                        inner,
                        type_name: value.type_name(),
                    })
                })
                .collect::<Result<Vec<_>, _>>()
                .map(Row::List),
            other => Err(NotATable::Item {
                item,
                type_name: other.type_name(),
            }),
        }
    }

    fn value(&self) -> Value {
        match self {
            Row::Scalar(cell) => cell.value(),
            Row::Triple { xyz, vector: false } => Value::Point(DVec3::from_array(*xyz)),
            Row::Triple { xyz, vector: true } => Value::Vector(DVec3::from_array(*xyz)),
            Row::List(cells) => Value::list(cells.iter().map(Cell::value).collect()),
        }
    }

    /// The number of cells.
    pub fn width(&self) -> usize {
        match self {
            Row::Scalar(_) => 1,
            Row::Triple { .. } => 3,
            Row::List(cells) => cells.len(),
        }
    }

    /// Cell `c` (a coordinate of a point is a number cell).
    pub fn cell(&self, c: usize) -> Option<Cell> {
        match self {
            Row::Scalar(cell) => (c == 0).then(|| cell.clone()),
            Row::Triple { xyz, .. } => xyz.get(c).map(|x| Cell::Number(*x)),
            Row::List(cells) => cells.get(c).cloned(),
        }
    }

    /// Sets cell `c` from `text`, read as the cell's kind.
    fn set(&mut self, c: usize, text: &str) -> Result<(), CellError> {
        match self {
            Row::Scalar(cell) if c == 0 => *cell = cell.parse_like(text)?,
            Row::Triple { xyz, .. } if c < 3 => xyz[c] = tsv::parse_number(text)?,
            Row::List(cells) if c < cells.len() => cells[c] = cells[c].parse_like(text)?,
            _ => return Err(CellError::NoColumn(c)),
        }
        Ok(())
    }

    fn texts(&self) -> Vec<String> {
        (0..self.width())
            .filter_map(|c| self.cell(c).map(|cell| cell.text()))
            .collect()
    }
}

/// `x + (y − x)·t` when finite, else `fallback`.
fn blend(x: f64, y: f64, t: f64, fallback: f64) -> f64 {
    let v = x + (y - x) * t;
    if v.is_finite() { v } else { fallback }
}

/// The row `from + (to − from)·t` where both have the same shape (numbers blend, other cells are
/// those of `base`), else a copy of `base`.
fn blend_rows(from: &Row, to: &Row, t: f64, base: &Row) -> Row {
    let base_number = |c: usize, fallback: f64| match base.cell(c) {
        Some(Cell::Number(x)) => x,
        _ => fallback,
    };
    match (from, to) {
        (Row::Scalar(Cell::Number(x)), Row::Scalar(Cell::Number(y)))
            if matches!(base, Row::Scalar(Cell::Number(_))) =>
        {
            Row::Scalar(Cell::Number(blend(*x, *y, t, base_number(0, *y))))
        }
        (Row::Triple { xyz: p, vector: v }, Row::Triple { xyz: q, vector: w })
            if v == w && matches!(base, Row::Triple { vector, .. } if vector == v) =>
        {
            Row::Triple {
                xyz: [0, 1, 2].map(|i| blend(p[i], q[i], t, base_number(i, q[i]))),
                vector: *v,
            }
        }
        (Row::List(a), Row::List(b)) if a.len() == b.len() && base.width() == a.len() => Row::List(
            (0..a.len())
                .map(|c| match (&a[c], &b[c], base.cell(c)) {
                    (Cell::Number(x), Cell::Number(y), Some(Cell::Number(z))) => {
                        Cell::Number(blend(*x, *y, t, z))
                    }
                    (_, _, cell) => cell.unwrap_or(Cell::Null),
                })
                .collect(),
        ),
        _ => base.clone(),
    }
}

/// What an input takes, for the rows its value does not show (an empty list, added rows).
#[derive(Clone, Debug, PartialEq)]
pub struct ItemType {
    /// The item type (`Any`: numbers).
    pub item: ValueType,
    /// Whether the input takes tables (lists of lists): table or tree access.
    pub tables: bool,
}

/// How the table's columns read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Points or vectors: x, y, z.
    Xyz,
    /// One value a row.
    Column,
    /// Rows of values (rows may differ in length): columns 0, 1, 2…
    Table,
}

/// A literal list as rows of cells (see the module doc).
#[derive(Clone, Debug)]
pub struct Table {
    rows: Vec<Row>,
    /// `Some(closed)` when the value is a polyline (its points are the rows).
    polyline: Option<bool>,
    /// The row added to an empty table.
    template: Row,
    /// Rows may be lists (the input takes tables).
    tables: bool,
    /// Points of a table of numbers are three-number rows (`param.list` of numbers: the file
    /// reader takes `[a, b, c]` for a point).
    triples_are_rows: bool,
}

impl Table {
    /// The table of `value` (`None`: no value yet, an empty list), for an input taking `items`.
    /// Fails, saying why, for values that are not lists of cells, points or rows of cells.
    pub fn new(value: Option<&Value>, items: &ItemType) -> Result<Table, NotATable> {
        let template = match items.item {
            ValueType::Point | ValueType::Polyline => Row::Triple {
                xyz: [0.0; 3],
                vector: false,
            },
            ValueType::Vector => Row::Triple {
                xyz: [0.0; 3],
                vector: true,
            },
            ValueType::Integer => Row::Scalar(Cell::Integer(0)),
            ValueType::Boolean => Row::Scalar(Cell::Boolean(false)),
            ValueType::Text => Row::Scalar(Cell::Text(Arc::from(""))),
            _ => Row::Scalar(Cell::Number(0.0)),
        };
        let mut table = Table {
            rows: Vec::new(),
            polyline: None,
            template,
            tables: items.tables,
            triples_are_rows: items.tables
                && matches!(items.item, ValueType::Number | ValueType::Integer),
        };
        match value {
            None | Some(Value::Null) => {
                if items.item == ValueType::Polyline {
                    table.polyline = Some(false);
                }
            }
            Some(Value::Polyline(p)) => {
                table.polyline = Some(p.closed);
                table.rows = p
                    .points
                    .iter()
                    .map(|p| Row::Triple {
                        xyz: p.to_array(),
                        vector: false,
                    })
                    .collect();
            }
            Some(Value::List(items)) => {
                // Sized once: a list of millions of items is not grown by doubling.
                table.rows = Vec::with_capacity(items.len());
                for (k, item) in items.iter().enumerate() {
                    table.rows.push(Row::of(k, item)?);
                }
            }
            Some(other) => return Err(NotATable::Single(other.type_name())),
        }
        Ok(table)
    }

    /// Whether [`Table::new`] takes `value`, found without building the table (a large list is
    /// only walked).
    pub fn accepts(value: Option<&Value>) -> bool {
        match value {
            None | Some(Value::Null) | Some(Value::Polyline(_)) => true,
            Some(Value::List(items)) => items
                .iter()
                .enumerate()
                .all(|(k, item)| Row::of(k, item).is_ok()),
            Some(_) => false,
        }
    }

    /// The value the table holds (untouched items as they were, bit for bit).
    pub fn to_value(&self) -> Value {
        match self.polyline {
            Some(closed) => Value::Polyline(Arc::new(Polyline {
                points: self
                    .rows
                    .iter()
                    .map(|r| match r {
                        Row::Triple { xyz, .. } => DVec3::from_array(*xyz),
                        _ => DVec3::ZERO,
                    })
                    .collect(),
                closed,
            })),
            None => Value::list(self.rows.iter().map(Row::value).collect()),
        }
    }

    /// The rows.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// True when there are no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Rows to read the layout from: the rows, or the row an empty table would get.
    fn shape_rows(&self) -> &[Row] {
        if self.rows.is_empty() {
            std::slice::from_ref(&self.template)
        } else {
            &self.rows
        }
    }

    /// How the columns read.
    pub fn layout(&self) -> Layout {
        let rows = self.shape_rows();
        if !self.triples_are_rows && rows.iter().all(|r| matches!(r, Row::Triple { .. })) {
            Layout::Xyz
        } else if rows.iter().all(|r| matches!(r, Row::Scalar(_))) {
            Layout::Column
        } else {
            Layout::Table
        }
    }

    /// The number of columns (of the widest row).
    pub fn width(&self) -> usize {
        self.shape_rows().iter().map(Row::width).max().unwrap_or(0)
    }

    /// The title of column `c`: x, y, z; the kind of a one-column list; else its index.
    pub fn column_name(&self, c: usize) -> String {
        match self.layout() {
            Layout::Xyz => ["x", "y", "z"]
                .get(c)
                .map_or_else(String::new, |s| s.to_string()),
            Layout::Column => {
                let kinds: BTreeSet<&str> = self
                    .shape_rows()
                    .iter()
                    .filter_map(|r| r.cell(0))
                    .map(|cell| cell.kind_name())
                    .collect();
                match kinds.into_iter().collect::<Vec<_>>()[..] {
                    [kind] => kind.to_string(),
                    _ => "value".to_string(),
                }
            }
            Layout::Table => c.to_string(),
        }
    }

    /// The name of cell (r, c) in messages and for screen readers: `row 3 y`, `row 3`,
    /// `row 3, column 5`.
    pub fn cell_name(&self, r: usize, c: usize) -> String {
        match self.layout() {
            Layout::Xyz => format!("row {r} {}", self.column_name(c)),
            Layout::Column => format!("row {r}"),
            Layout::Table => format!("row {r}, column {c}"),
        }
    }

    /// The text of cell (r, c), in full.
    pub fn text(&self, r: usize, c: usize) -> Option<String> {
        self.rows.get(r)?.cell(c).map(|cell| cell.text())
    }

    /// Sets cell (r, c) from `text`, read as that cell's kind. Returns whether the value changed;
    /// on an error (naming the cell) nothing changes.
    pub fn set_cell(&mut self, r: usize, c: usize, text: &str) -> Result<bool, TableEditError> {
        let cell = self.cell_name(r, c);
        let Some(row) = self.rows.get_mut(r) else {
            return Err(TableEditError::RowGone { cell, row: r });
        };
        let before = row.value();
        let mut edited = row.clone();
        edited
            .set(c, text)
            .map_err(|error| TableEditError::Cell { cell, error })?;
        let changed = !edited.value().same_as(&before);
        if changed {
            *row = edited;
        }
        Ok(changed)
    }

    /// Adds a row after row `after` (`None`: at the end) and returns its index. Between two rows
    /// of the same shape its numbers are their midpoints; at the end they continue the step
    /// from the row before the last; other cells (and rows of other shapes) copy the row above.
    /// An empty table gets a row of zeros of the input's item type.
    pub fn add_row(&mut self, after: Option<usize>) -> usize {
        let n = self.rows.len();
        let at = after.map_or(n, |a| (a + 1).min(n));
        let row = if n == 0 {
            self.template.clone()
        } else if at == 0 {
            self.rows[0].clone()
        } else if at < n {
            blend_rows(&self.rows[at - 1], &self.rows[at], 0.5, &self.rows[at - 1])
        } else if n >= 2 {
            blend_rows(&self.rows[n - 2], &self.rows[n - 1], 2.0, &self.rows[n - 1])
        } else {
            self.rows[n - 1].clone()
        };
        self.rows.insert(at, row);
        at
    }

    /// Removes the rows `rows` (indices beyond the table are ignored); returns how many went.
    pub fn remove_rows(&mut self, rows: &BTreeSet<usize>) -> usize {
        let before = self.rows.len();
        let mut k = 0;
        self.rows.retain(|_| {
            let keep = !rows.contains(&k);
            k += 1;
            keep
        });
        before - self.rows.len()
    }

    /// A single pasted line of several fields in a one-column list is read as a column.
    fn oriented(&self, lines: &[Vec<String>]) -> Vec<Vec<String>> {
        if self.layout() == Layout::Column && lines.len() == 1 && lines[0].len() > 1 {
            lines[0].iter().map(|f| vec![f.clone()]).collect()
        } else {
            lines.to_vec()
        }
    }

    /// Writes the pasted `lines` into the cells from (r, c) on, right and down; lines past the
    /// last row add rows (copies of the last row, then overwritten). Every field is read as the
    /// kind of the cell it lands on. On an error (naming the line and field of the text) nothing
    /// changes. Returns what was done, in words.
    pub fn paste_at(
        &mut self,
        r: usize,
        c: usize,
        lines: &[Vec<String>],
    ) -> Result<String, TableEditError> {
        let lines = self.oriented(lines);
        if lines.is_empty() {
            return Err(TableEditError::NothingToPaste);
        }
        let mut next = self.clone();
        let start = r.min(next.rows.len());
        let mut added = 0;
        for (i, fields) in lines.iter().enumerate() {
            let row = start + i;
            if row >= next.rows.len() {
                let copy = next.rows.last().unwrap_or(&next.template).clone();
                next.rows.push(copy);
                added += 1;
            }
            let width = next.rows[row].width();
            if c + fields.len() > width {
                return Err(TableEditError::DoesNotFit {
                    line: i + 1,
                    fields: fields.len(),
                    column: self.column_name(c),
                    row,
                    width,
                });
            }
            for (j, field) in fields.iter().enumerate() {
                next.rows[row]
                    .set(c + j, field)
                    .map_err(|error| TableEditError::Field {
                        line: i + 1,
                        field: j + 1,
                        error,
                    })?;
            }
        }
        *self = next;
        let mut done = format!(
            "pasted {} at {}",
            count(lines.len(), ("line", "lines")),
            self.cell_name(start, c)
        );
        if added > 0 {
            done.push_str(&format!(" ({} added)", count(added, ("row", "rows"))));
        }
        Ok(done)
    }

    /// Replaces every row by the pasted `lines`. Line k takes the shape and kinds of row k (past
    /// the old rows: of the last row; in an empty table: of the input's item type); a line of
    /// several fields makes a row of a table where the input takes tables. On an error (naming the
    /// line and field of the text) nothing changes. Returns what was done, in words.
    pub fn replace_all(&mut self, lines: &[Vec<String>]) -> Result<String, TableEditError> {
        let lines = self.oriented(lines);
        if lines.is_empty() {
            return Err(TableEditError::NothingToPaste);
        }
        let layout = self.layout();
        let rows = lines
            .iter()
            .enumerate()
            .map(|(i, fields)| {
                let like = self
                    .rows
                    .get(i)
                    .or(self.rows.last())
                    .unwrap_or(&self.template);
                self.row_from_fields(i + 1, like, fields, layout)
            })
            .collect::<Result<Vec<_>, _>>()?;
        self.rows = rows;
        Ok(format!("replaced all rows: {} now", self.rows.len()))
    }

    /// A row of the shape and kinds of `like` read from `fields`, line `line` of a paste.
    fn row_from_fields(
        &self,
        line: usize,
        like: &Row,
        fields: &[String],
        layout: Layout,
    ) -> Result<Row, TableEditError> {
        let field_error = |j: usize| {
            move |error| TableEditError::Field {
                line,
                field: j + 1,
                error,
            }
        };
        let parse = |j: usize, kind: &Cell| kind.parse_like(&fields[j]).map_err(field_error(j));
        let number = Cell::Number(0.0);
        match like {
            Row::Triple { vector, .. } if fields.len() == 3 => {
                let mut xyz = [0.0; 3];
                for (j, x) in xyz.iter_mut().enumerate() {
                    *x = tsv::parse_number(&fields[j]).map_err(field_error(j))?;
                }
                Ok(Row::Triple {
                    xyz,
                    vector: *vector,
                })
            }
            Row::Triple { .. }
                if self.polyline.is_some() || layout == Layout::Xyz || !self.tables =>
            {
                Err(TableEditError::NotAPoint {
                    line,
                    fields: fields.len(),
                })
            }
            Row::Triple { .. } => (0..fields.len())
                .map(|j| parse(j, &number))
                .collect::<Result<_, _>>()
                .map(Row::List),
            Row::Scalar(cell) if fields.len() == 1 => Ok(Row::Scalar(parse(0, cell)?)),
            Row::Scalar(cell) if self.tables => (0..fields.len())
                .map(|j| parse(j, cell))
                .collect::<Result<_, _>>()
                .map(Row::List),
            Row::Scalar(_) => Err(TableEditError::OneColumn {
                line,
                fields: fields.len(),
            }),
            Row::List(cells) => (0..fields.len())
                .map(|j| parse(j, cells.get(j).or(cells.last()).unwrap_or(&number)))
                .collect::<Result<_, _>>()
                .map(Row::List),
        }
    }

    /// The rows (all, or those in `only`) as tab-separated text, numbers in full.
    pub fn to_tsv(&self, only: Option<&BTreeSet<usize>>) -> String {
        let lines: Vec<Vec<String>> = self
            .rows
            .iter()
            .enumerate()
            .filter(|(k, _)| only.is_none_or(|o| o.contains(k)))
            .map(|(_, r)| r.texts())
            .collect();
        tsv::format(&lines)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn points(ps: &[[f64; 3]]) -> Value {
        Value::list(
            ps.iter()
                .map(|p| Value::Point(DVec3::from_array(*p)))
                .collect(),
        )
    }

    fn of(ty: ValueType, tables: bool) -> ItemType {
        ItemType { item: ty, tables }
    }

    fn lines(text: &str) -> Vec<Vec<String>> {
        tsv::parse(text)
    }

    #[test]
    fn accepts_says_what_new_makes_a_table_of() {
        let values = [
            None,
            Some(Value::Null),
            Some(Value::Number(1.0)),
            Some(Value::text("a")),
            Some(points(&[[0.0, 1.0, 2.0]])),
            Some(Value::list(vec![Value::Number(1.0), Value::Integer(2)])),
            Some(Value::list(vec![Value::list(vec![Value::Number(1.0)])])),
            Some(Value::list(vec![Value::list(vec![Value::list(vec![])])])),
            Some(Value::list(vec![Value::Number(1.0), Value::text("b")])),
            Some(Value::from(cnets_geometry::Polyline {
                points: vec![DVec3::ZERO],
                closed: true,
            })),
        ];
        for value in &values {
            for ty in [ValueType::Number, ValueType::Point, ValueType::Text] {
                assert_eq!(
                    Table::accepts(value.as_ref()),
                    Table::new(value.as_ref(), &of(ty.clone(), true)).is_ok(),
                    "{value:?} as {ty:?}"
                );
            }
        }
    }

    /// Every item except `changed` is the same value bit for bit.
    fn same_except(a: &Value, b: &Value, changed: &[usize]) {
        let (a, b) = (a.as_list().unwrap(), b.as_list().unwrap());
        assert_eq!(a.len(), b.len(), "the length is kept");
        for k in 0..a.len() {
            if !changed.contains(&k) {
                assert!(
                    a[k].same_as(&b[k]),
                    "item {k}: {:?} became {:?}",
                    a[k],
                    b[k]
                );
            }
        }
    }

    /// A table of numbers as `param.list` holds one: rows of numbers, a 3-number row read as a
    /// point, a row with an integer.
    fn ragged_table() -> Value {
        Value::list(vec![
            Value::list(vec![
                0.1.into(),
                0.2.into(),
                0.30000000000000004.into(),
                0.4.into(),
            ]),
            Value::Point(DVec3::new(1.0, 2.0, 3.0)),
            Value::list(vec![Value::Integer(7), 0.5.into()]),
        ])
    }

    #[test]
    fn every_supported_value_reads_back_bit_for_bit() {
        let mixed = Value::list(vec![
            Value::Number(0.1),
            Value::Integer(-3),
            Value::Boolean(true),
            Value::text("a\tb"),
            Value::Null,
            Value::Number(-0.0),
        ]);
        let vectors = Value::list(vec![Value::Vector(DVec3::new(1e-300, -0.0, 7.5))]);
        let polyline = Value::Polyline(Arc::new(Polyline {
            points: vec![DVec3::ZERO, DVec3::new(0.1, 0.2, 0.3)],
            closed: true,
        }));
        let packed = Value::List(cnets_engine::Items::numbers(
            Arc::new(vec![0.5, 1.0 / 3.0, 2.0]),
            0..3,
        ));
        for (v, ty, tables) in [
            (mixed, ValueType::Any, true),
            (vectors, ValueType::Vector, false),
            (polyline, ValueType::Polyline, false),
            (ragged_table(), ValueType::Any, true),
            (packed, ValueType::Number, false),
            (
                points(&[[0.0, -0.5, 0.0], [8.0, 0.7, 0.0]]),
                ValueType::Point,
                false,
            ),
        ] {
            let t = Table::new(Some(&v), &of(ty, tables)).unwrap();
            assert!(t.to_value().same_as(&v), "{v:?}");
            // And through its own TSV, replacing all rows.
            let mut back = t.clone();
            back.replace_all(&lines(&t.to_tsv(None))).unwrap();
            assert!(back.to_value().same_as(&v), "TSV round trip of {v:?}");
        }
    }

    #[test]
    fn values_that_are_not_tables_are_refused_saying_why() {
        let polylines = Value::list(vec![Value::Polyline(Arc::new(Polyline::open(vec![])))]);
        let e = Table::new(Some(&polylines), &of(ValueType::Any, true)).unwrap_err();
        assert_eq!(e.to_string(), "item 0: it is a polyline");
        let deep = Value::list(vec![points(&[[0.0; 3]])]);
        let e = Table::new(Some(&deep), &of(ValueType::Any, true)).unwrap_err();
        assert_eq!(e.to_string(), "item 0: its item 0 is a point");
        assert!(Table::new(Some(&Value::Number(1.0)), &of(ValueType::Number, false)).is_err());
    }

    #[test]
    fn layouts_and_column_names() {
        let t = Table::new(Some(&points(&[[0.0; 3]])), &of(ValueType::Point, false)).unwrap();
        assert_eq!(
            (t.layout(), t.width(), t.column_name(1)),
            (Layout::Xyz, 3, "y".into())
        );
        assert_eq!(t.cell_name(0, 2), "row 0 z");
        let ints = Value::list(vec![Value::Integer(1), Value::Integer(2)]);
        let t = Table::new(Some(&ints), &of(ValueType::Integer, false)).unwrap();
        assert_eq!(
            (t.layout(), t.column_name(0)),
            (Layout::Column, "integer".into())
        );
        let t = Table::new(Some(&ragged_table()), &of(ValueType::Number, true)).unwrap();
        assert_eq!((t.layout(), t.width()), (Layout::Table, 4));
        assert_eq!(t.cell_name(2, 1), "row 2, column 1");
        // A param.list of numbers whose rows all have three numbers is still a table.
        let t = Table::new(
            Some(&points(&[[1.0, 2.0, 3.0]])),
            &of(ValueType::Number, true),
        )
        .unwrap();
        assert_eq!(t.layout(), Layout::Table);
        let empty = Table::new(None, &of(ValueType::Vector, false)).unwrap();
        assert_eq!((empty.layout(), empty.len()), (Layout::Xyz, 0));
    }

    #[test]
    fn a_cell_edit_changes_that_number_only_and_keeps_kinds() {
        let v = points(&[[0.0, -0.5, 0.0], [8.0, 0.7, 0.0], [16.0, 0.1, 0.2]]);
        let mut t = Table::new(Some(&v), &of(ValueType::Point, false)).unwrap();
        assert_eq!(t.set_cell(1, 1, "0.40179139375686646"), Ok(true));
        let after = t.to_value();
        same_except(&v, &after, &[1]);
        assert!(
            after.as_list().unwrap()[1].same_as(&Value::Point(DVec3::new(
                8.0,
                0.401_791_393_756_866_46,
                0.0
            )))
        );
        assert_eq!(
            t.text(1, 1).unwrap(),
            "0.40179139375686646",
            "shown in full"
        );
        // The same number typed differently is no change.
        assert_eq!(t.set_cell(0, 0, "0.000"), Ok(false));
        // Kinds stay: a vector stays a vector, an integer an integer.
        let mixed = Value::list(vec![Value::Vector(DVec3::X), Value::Integer(4)]);
        let mut t = Table::new(Some(&mixed), &of(ValueType::Any, true)).unwrap();
        t.set_cell(0, 2, "2.5").unwrap();
        t.set_cell(1, 0, "5").unwrap();
        let after = t.to_value();
        let items = after.as_list().unwrap();
        assert!(items[0].same_as(&Value::Vector(DVec3::new(1.0, 0.0, 2.5))));
        assert!(items[1].same_as(&Value::Integer(5)));
        // A bad cell is refused naming it, and nothing changes.
        let e = t.set_cell(1, 0, "5.5").unwrap_err();
        assert_eq!(
            e.to_string(),
            "row 1, column 0: '5.5' is not a whole number"
        );
        assert!(t.to_value().same_as(&after));
        assert!(
            t.set_cell(0, 0, "1,5")
                .unwrap_err()
                .to_string()
                .contains("'.' as the decimal point")
        );
    }

    #[test]
    fn a_cell_of_a_ragged_table_keeps_the_table() {
        let v = ragged_table();
        let mut t = Table::new(Some(&v), &of(ValueType::Any, true)).unwrap();
        t.set_cell(0, 3, "0.45").unwrap();
        t.set_cell(1, 2, "4").unwrap();
        t.set_cell(2, 0, "8").unwrap();
        let after = t.to_value();
        let rows = after.as_list().unwrap();
        let first = rows[0].as_list().unwrap();
        assert_eq!(first.len(), 4);
        assert!(
            first[..3]
                .iter()
                .zip(v.as_list().unwrap()[0].as_list().unwrap())
                .all(|(a, b)| a.same_as(b))
        );
        assert!(first[3].same_as(&Value::Number(0.45)));
        assert!(
            rows[1].same_as(&Value::Point(DVec3::new(1.0, 2.0, 4.0))),
            "a point row stays a point"
        );
        assert!(rows[2].same_as(&Value::list(vec![Value::Integer(8), 0.5.into()])));
        assert!(t.set_cell(2, 2, "1").is_err(), "row 2 has two cells");
    }

    #[test]
    fn added_rows_interpolate_extrapolate_or_copy() {
        let v = points(&[[0.0, 0.0, 0.0], [2.0, 4.0, 0.0]]);
        let mut t = Table::new(Some(&v), &of(ValueType::Point, false)).unwrap();
        assert_eq!(t.add_row(Some(0)), 1, "after row 0");
        assert_eq!(t.add_row(None), 3, "at the end");
        let after = t.to_value();
        let expected = points(&[
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [2.0, 4.0, 0.0],
            [3.0, 6.0, 0.0],
        ]);
        assert!(after.same_as(&expected), "{after:?}");
        // Integers and texts copy the row above; one row is copied; a vector stays a vector.
        let ints = Value::list(vec![Value::Integer(1), Value::Integer(5)]);
        let mut t = Table::new(Some(&ints), &of(ValueType::Integer, false)).unwrap();
        t.add_row(Some(0));
        assert!(t.to_value().same_as(&Value::list(vec![
            Value::Integer(1),
            Value::Integer(1),
            Value::Integer(5)
        ])));
        let one = Value::list(vec![Value::Vector(DVec3::Y)]);
        let mut t = Table::new(Some(&one), &of(ValueType::Vector, false)).unwrap();
        t.add_row(None);
        assert!(
            t.to_value()
                .same_as(&Value::list(vec![Value::Vector(DVec3::Y); 2]))
        );
        // A table row gets the midpoints of its neighbours' numbers.
        let table = Value::list(vec![
            Value::list(vec![0.0.into(), 1.0.into()]),
            Value::list(vec![1.0.into(), 3.0.into()]),
        ]);
        let mut t = Table::new(Some(&table), &of(ValueType::Number, true)).unwrap();
        t.add_row(Some(0));
        let rows = t.to_value();
        assert!(rows.as_list().unwrap()[1].same_as(&Value::list(vec![0.5.into(), 2.0.into()])));
        assert_eq!(rows.as_list().unwrap().len(), 3);
        // An empty list gets a row of the item type.
        let mut t = Table::new(None, &of(ValueType::Vector, false)).unwrap();
        t.add_row(None);
        assert!(
            t.to_value()
                .same_as(&Value::list(vec![Value::Vector(DVec3::ZERO)]))
        );
    }

    #[test]
    fn removed_rows_leave_the_others_untouched() {
        let v = points(&[[0.0; 3], [1.0; 3], [2.0; 3], [3.0; 3]]);
        let mut t = Table::new(Some(&v), &of(ValueType::Point, false)).unwrap();
        assert_eq!(t.remove_rows(&BTreeSet::from([1, 3, 9])), 2);
        assert!(t.to_value().same_as(&points(&[[0.0; 3], [2.0; 3]])));
        let poly = Value::Polyline(Arc::new(Polyline {
            points: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            closed: true,
        }));
        let mut t = Table::new(Some(&poly), &of(ValueType::Polyline, false)).unwrap();
        t.remove_rows(&BTreeSet::from([0]));
        let Value::Polyline(p) = t.to_value() else {
            panic!("a polyline stays a polyline")
        };
        assert_eq!(
            (p.points.clone(), p.closed),
            (vec![DVec3::X, DVec3::Y], true)
        );
    }

    #[test]
    fn paste_at_a_cell_writes_right_and_down_and_adds_rows() {
        let v = points(&[[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
        let mut t = Table::new(Some(&v), &of(ValueType::Point, false)).unwrap();
        let done = t.paste_at(1, 1, &lines("5\t6\n7\t8\n9\t10\n")).unwrap();
        assert_eq!(done, "pasted 3 lines at row 1 y (2 rows added)");
        let after = t.to_value();
        let expected = points(&[
            [0.0, 0.0, 0.0],
            [1.0, 5.0, 6.0],
            [1.0, 7.0, 8.0],
            [1.0, 9.0, 10.0],
        ]);
        assert!(after.same_as(&expected), "{after:?}");
        // Too wide, or a bad field: refused, naming the line and field, nothing changed.
        let e = t.paste_at(0, 2, &lines("1,2")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("line 1: 2 fields from column z do not fit"),
            "{e}"
        );
        let e = t.paste_at(0, 0, &lines("1;2;3\n4;x;6")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 2, field 2: 'x' is not a number; nothing was pasted"
        );
        assert!(t.to_value().same_as(&expected));
        // One line of several fields into a one-column list is a column.
        let numbers = Value::list(vec![0.0.into(), 0.0.into(), 0.0.into()]);
        let mut t = Table::new(Some(&numbers), &of(ValueType::Number, false)).unwrap();
        t.paste_at(1, 0, &lines("0.25\t0.5")).unwrap();
        assert!(
            t.to_value()
                .same_as(&Value::list(vec![0.0.into(), 0.25.into(), 0.5.into()]))
        );
    }

    #[test]
    fn replacing_all_keeps_kinds_and_a_table_stays_a_table() {
        let v = ragged_table();
        let mut t = Table::new(Some(&v), &of(ValueType::Number, true)).unwrap();
        t.replace_all(&lines("1,2\n3,4,5\n6,7\n8,9,10,11")).unwrap();
        let after = t.to_value();
        let expected = Value::list(vec![
            Value::list(vec![1.0.into(), 2.0.into()]),
            Value::Point(DVec3::new(3.0, 4.0, 5.0)),
            Value::list(vec![Value::Integer(6), 7.0.into()]),
            Value::list(vec![
                Value::Integer(8),
                9.0.into(),
                10.0.into(),
                11.0.into(),
            ]),
        ]);
        assert!(after.same_as(&expected), "{after:?}");
        // Points need three fields; a one-column list one.
        let mut p = Table::new(Some(&points(&[[0.0; 3]])), &of(ValueType::Point, false)).unwrap();
        let e = p.replace_all(&lines("1\t2\t3\n4\t5")).unwrap_err();
        assert_eq!(e, TableEditError::NotAPoint { line: 2, fields: 2 });
        assert_eq!(
            e.to_string(),
            "line 2: 2 fields, but points need 3 (x, y, z); nothing was pasted"
        );
        let texts = Value::list(vec![Value::text("a")]);
        let mut c = Table::new(Some(&texts), &of(ValueType::Text, false)).unwrap();
        assert!(c.replace_all(&lines("a\tb\nc\td")).is_err());
        c.replace_all(&lines("x\n\"y, z\"\n")).unwrap();
        assert!(
            c.to_value()
                .same_as(&Value::list(vec![Value::text("x"), Value::text("y, z")]))
        );
        // Vectors stay vectors; an empty list of points takes points.
        let vectors = Value::list(vec![Value::Vector(DVec3::Z)]);
        let mut t = Table::new(Some(&vectors), &of(ValueType::Any, true)).unwrap();
        t.replace_all(&lines("1 ,2,3\n4,5,6")).unwrap();
        assert!(t.to_value().same_as(&Value::list(vec![
            Value::Vector(DVec3::new(1.0, 2.0, 3.0)),
            Value::Vector(DVec3::new(4.0, 5.0, 6.0)),
        ])));
        let mut t = Table::new(None, &of(ValueType::Point, false)).unwrap();
        t.replace_all(&lines("1\t2\t3")).unwrap();
        assert!(t.to_value().same_as(&points(&[[1.0, 2.0, 3.0]])));
    }

    #[test]
    fn copies_selected_rows_as_tsv_in_full() {
        let v = Value::list(vec![
            Value::Point(DVec3::new(0.1, 1.0 / 3.0, -0.0)),
            Value::Point(DVec3::new(1e-7, 2.0, 3.0)),
        ]);
        let t = Table::new(Some(&v), &of(ValueType::Point, false)).unwrap();
        assert_eq!(t.to_tsv(None), "0.1\t0.3333333333333333\t-0\n1e-7\t2\t3\n");
        assert_eq!(t.to_tsv(Some(&BTreeSet::from([1]))), "1e-7\t2\t3\n");
    }
}
