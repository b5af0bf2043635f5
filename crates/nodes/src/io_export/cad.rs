//! DXF cutting drawings, written directly as ASCII DXF R2000 (AC1015) group codes.
//!
//! The `dxf` crate wrote this file before; it was replaced because its table headers had no handles
//! and no true entry counts (ezdxf's audit repaired 7 things), its files carried a creation time
//! and random GUIDs (two runs differed), and writing 80 000 outlines took about 50 s growing
//! quadratically (a linear search per added layer and handle). The writer here emits the minimal
//! complete R2000 structure — HEADER (`$ACADVER`, `$HANDSEED`, `$INSUNITS` = 4 mm, `$MEASUREMENT` = 1
//! metric, `$EXTMIN`/`$EXTMAX` = the drawing's extents), empty CLASSES, the nine symbol tables with
//! handles and true counts, the model and paper space blocks, the ENTITIES, and the OBJECTS root
//! dictionary with its groups and layouts — in one pass, linear in the outlines, with handles
//! counted from fixed values: the same sheet gives the same bytes. `crates/nodes/tests/
//! export_dxf_ezdxf.rs` runs ezdxf's audit on it (zero errors, zero fixes).
//!
//! Every outline is an LWPOLYLINE (closed flag set for closed outlines) on its own layer
//! `STRIP_<label>` (or `STRIP_<k>`; prefixed `SHEET<s>_` when the outlines are nested on sheets, so
//! each sheet is a group of layers), with its label as a TEXT entity on the same layer, centred on
//! the label point. Coordinates are the model's x and y times `scale` (no offset).
//!
//! With fold lines or marks (issue 43) the drawing is on the workshop layers instead: outlines on
//! `CUT`, their labels on `TEXT`, fold lines on `FOLDS` each with its signed angle (`+12.50`,
//! degrees, mountain positive) as TEXT at its middle, marks on `MARKS` with their labels as TEXT at
//! the mark's inner end; the texts run along their lines.
//!
//! With sheets (`fab.nest`) every sheet is one block `SHEET_<s+1>` holding that sheet's outlines,
//! labels, fold lines and marks (each line on the sheet of the outline it lies on), its base point
//! the lower-left corner of its contents, and the model space holds one INSERT of each block at its
//! base point, so the drawing shows the nested layout and a CAM program can take one sheet (one
//! block) at a time. The entities keep their layers inside the blocks.

use std::collections::HashSet;
use std::fmt::Write;

use glam::DVec2;

use super::outlines::Sheet;

/// The layer name of outline `k`: `STRIP_` and its label reduced to letters, digits, `_` and `-`
/// (made unique with `_k`, repeated as needed, while a layer of that name — upper-cased — is `taken`).
pub fn layer_name(label: &str, k: usize, taken: &HashSet<String>) -> String {
    let clean: String = label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let base = if clean.is_empty() {
        format!("STRIP_{k}")
    } else {
        format!("STRIP_{clean}")
    };
    let mut name = base;
    while taken.contains(&name.to_ascii_uppercase()) {
        name = format!("{name}_{k}");
    }
    name
}

/// Handles of the fixed objects (the symbol tables, the root dictionaries).
mod handle {
    pub const VPORT: u64 = 0x1;
    pub const LTYPE: u64 = 0x2;
    pub const LAYER: u64 = 0x3;
    pub const STYLE: u64 = 0x4;
    pub const VIEW: u64 = 0x5;
    pub const UCS: u64 = 0x6;
    pub const APPID: u64 = 0x7;
    pub const DIMSTYLE: u64 = 0x8;
    pub const BLOCK_RECORD: u64 = 0x9;
    pub const ROOT: u64 = 0xA;
    pub const GROUPS: u64 = 0xB;
    pub const LAYOUTS: u64 = 0xC;
    /// The first handle handed out by [`super::Writer::next`].
    pub const FIRST_FREE: u64 = 0x10;
}

/// The DXF text being written and the next free handle.
struct Writer {
    out: String,
    next: u64,
}

impl Writer {
    /// A new handle.
    fn next(&mut self) -> u64 {
        self.next += 1;
        self.next - 1
    }

    /// One group: the code right-aligned in 3 columns, then the value, each on its line.
    fn group(&mut self, code: u16, value: impl std::fmt::Display) {
        let _ = write!(self.out, "{code:>3}\n{value}\n");
    }

    /// A handle group (hexadecimal, upper case).
    fn handle(&mut self, code: u16, h: u64) {
        let _ = write!(self.out, "{code:>3}\n{h:X}\n");
    }

    /// A real number: shortest round-trip form, always with a decimal point or exponent.
    fn real(&mut self, code: u16, x: f64) {
        let _ = write!(self.out, "{code:>3}\n{x:?}\n");
    }

    /// The header of a symbol table with its handle and true entry count.
    fn table(&mut self, name: &str, h: u64, count: usize) {
        self.group(0, "TABLE");
        self.group(2, name);
        self.handle(5, h);
        self.group(330, 0);
        self.group(100, "AcDbSymbolTable");
        self.group(70, count);
    }

    /// The start of a symbol table record.
    fn record(&mut self, kind: &str, subclass: &str, h: u64, owner: u64, name: &str) {
        self.group(0, kind);
        self.handle(if kind == "DIMSTYLE" { 105 } else { 5 }, h);
        self.handle(330, owner);
        self.group(100, "AcDbSymbolTableRecord");
        self.group(100, subclass);
        self.group(2, name);
        self.group(70, 0);
    }
}

/// The layers of a drawing with folds or marks: name and colour index (red cut lines, blue folds,
/// green marks, white/black text).
const WORKSHOP_LAYERS: [(&str, usize); 4] = [("CUT", 1), ("FOLDS", 5), ("MARKS", 3), ("TEXT", 7)];

/// One layer, in drawing order.
struct LayerEntry {
    name: String,
    colour: usize,
    handle: u64,
}

/// Encodes the sheet as a DXF drawing.
pub fn encode_dxf(sheet: &Sheet) -> Result<Vec<u8>, String> {
    let points: usize = sheet.paths.iter().map(|(p, _)| p.len()).sum();
    let mut w = Writer {
        out: String::with_capacity(4096 + 48 * points + 256 * sheet.paths.len()),
        next: handle::FIRST_FREE,
    };
    // Handles, in a fixed order.
    let (ms_record, ps_record) = (w.next(), w.next());
    let blocks = [w.next(), w.next(), w.next(), w.next()];
    let (ms_layout, ps_layout) = (w.next(), w.next());
    let vport = w.next();
    let ltypes = [w.next(), w.next(), w.next()];
    let layer0 = w.next();
    let (style, appid, dimstyle) = (w.next(), w.next(), w.next());
    let mut taken = HashSet::with_capacity(sheet.paths.len());
    let mut layers = Vec::with_capacity(sheet.paths.len());
    // The layer of every outline and of its label.
    let mut outline_layers: Vec<(usize, usize)> = Vec::with_capacity(sheet.paths.len());
    if sheet.is_workshop() {
        for (name, colour) in WORKSHOP_LAYERS {
            layers.push(LayerEntry {
                name: name.to_string(),
                colour,
                handle: w.next(),
            });
        }
        outline_layers.resize(sheet.paths.len(), (0, 3));
    } else {
        for (k, label) in sheet.labels.iter().enumerate() {
            let mut name = layer_name(label, k, &taken);
            taken.insert(name.to_ascii_uppercase());
            if let Some(sheets) = &sheet.sheets {
                name = format!("SHEET{}_{name}", sheets[k] + 1);
            }
            layers.push(LayerEntry {
                name,
                colour: k % 6 + 1,
                handle: w.next(),
            });
            outline_layers.push((k, k));
        }
    }
    let entity_handles: Vec<(u64, u64)> = (0..sheet.paths.len())
        .map(|_| (w.next(), w.next()))
        .collect();
    let line_handles: Vec<(u64, u64)> = (0..sheet.folds.len() + sheet.marks.len())
        .map(|_| (w.next(), w.next()))
        .collect();
    // One block per sheet, when the outlines are nested on sheets.
    let line_sheets = sheet.line_sheets();
    let sheet_blocks: Vec<SheetBlock> = sheet_contents(sheet, line_sheets.as_deref())
        .into_iter()
        .map(|(index, base)| SheetBlock {
            name: format!("SHEET_{}", index + 1),
            index,
            base,
            record: w.next(),
            begin: w.next(),
            end: w.next(),
            insert: w.next(),
        })
        .collect();
    let seed = w.next;

    let (lo, hi) = sheet.bounds;
    w.group(0, "SECTION");
    w.group(2, "HEADER");
    w.group(9, "$ACADVER");
    w.group(1, "AC1015");
    w.group(9, "$HANDSEED");
    w.handle(5, seed);
    w.group(9, "$INSUNITS");
    w.group(70, 4);
    w.group(9, "$MEASUREMENT");
    w.group(70, 1);
    for (name, p) in [("$EXTMIN", lo), ("$EXTMAX", hi)] {
        w.group(9, name);
        w.real(10, p.x);
        w.real(20, p.y);
        w.real(30, 0.0);
    }
    w.group(0, "ENDSEC");
    w.group(0, "SECTION");
    w.group(2, "CLASSES");
    w.group(0, "ENDSEC");

    w.group(0, "SECTION");
    w.group(2, "TABLES");
    w.table("VPORT", handle::VPORT, 1);
    w.record(
        "VPORT",
        "AcDbViewportTableRecord",
        vport,
        handle::VPORT,
        "*ACTIVE",
    );
    let centre = (lo + hi) * 0.5;
    let view_height = ((hi - lo).max_element() * 1.1).max(1.0);
    for (code, v) in [
        (10, 0.0),
        (20, 0.0),
        (11, 1.0),
        (21, 1.0),
        (12, centre.x),
        (22, centre.y),
        (13, 0.0),
        (23, 0.0),
        (14, 10.0),
        (24, 10.0),
        (15, 10.0),
        (25, 10.0),
        (16, 0.0),
        (26, 0.0),
        (36, 1.0),
        (17, 0.0),
        (27, 0.0),
        (37, 0.0),
        (40, view_height),
        (41, 2.0),
        (42, 50.0),
        (43, 0.0),
        (44, 0.0),
        (50, 0.0),
        (51, 0.0),
    ] {
        w.real(code, v);
    }
    for (code, v) in [(71, 0), (72, 100), (73, 1), (74, 3), (75, 0), (76, 0)] {
        w.group(code, v);
    }
    for (code, v) in [(77, 0), (78, 0)] {
        w.group(code, v);
    }
    w.group(0, "ENDTAB");

    w.table("LTYPE", handle::LTYPE, 3);
    for (h, name, description) in [
        (ltypes[0], "ByBlock", ""),
        (ltypes[1], "ByLayer", ""),
        (ltypes[2], "Continuous", "Solid line"),
    ] {
        w.record("LTYPE", "AcDbLinetypeTableRecord", h, handle::LTYPE, name);
        w.group(3, description);
        w.group(72, 65);
        w.group(73, 0);
        w.real(40, 0.0);
    }
    w.group(0, "ENDTAB");

    w.table("LAYER", handle::LAYER, 1 + layers.len());
    let layer_records = std::iter::once((layer0, "0", 7))
        .chain(layers.iter().map(|l| (l.handle, l.name.as_str(), l.colour)));
    for (h, name, colour) in layer_records {
        w.record("LAYER", "AcDbLayerTableRecord", h, handle::LAYER, name);
        w.group(62, colour);
        w.group(6, "Continuous");
        w.group(370, -3);
        w.group(390, 0);
    }
    w.group(0, "ENDTAB");

    let height = sheet.text_height();
    w.table("STYLE", handle::STYLE, 1);
    w.record(
        "STYLE",
        "AcDbTextStyleTableRecord",
        style,
        handle::STYLE,
        "Standard",
    );
    w.real(40, 0.0);
    w.real(41, 1.0);
    w.real(50, 0.0);
    w.group(71, 0);
    w.real(42, height);
    w.group(3, "txt");
    w.group(4, "");
    w.group(0, "ENDTAB");

    w.table("VIEW", handle::VIEW, 0);
    w.group(0, "ENDTAB");
    w.table("UCS", handle::UCS, 0);
    w.group(0, "ENDTAB");
    w.table("APPID", handle::APPID, 1);
    w.record(
        "APPID",
        "AcDbRegAppTableRecord",
        appid,
        handle::APPID,
        "ACAD",
    );
    w.group(0, "ENDTAB");
    w.table("DIMSTYLE", handle::DIMSTYLE, 1);
    w.group(100, "AcDbDimStyleTable");
    w.group(71, 0);
    w.record(
        "DIMSTYLE",
        "AcDbDimStyleTableRecord",
        dimstyle,
        handle::DIMSTYLE,
        "Standard",
    );
    w.group(0, "ENDTAB");
    w.table("BLOCK_RECORD", handle::BLOCK_RECORD, 2 + sheet_blocks.len());
    let records = [
        (ms_record, "*Model_Space", ms_layout),
        (ps_record, "*Paper_Space", ps_layout),
    ];
    let sheet_records = sheet_blocks.iter().map(|b| (b.record, b.name.as_str(), 0));
    for (h, name, layout) in records.into_iter().chain(sheet_records) {
        w.record(
            "BLOCK_RECORD",
            "AcDbBlockTableRecord",
            h,
            handle::BLOCK_RECORD,
            name,
        );
        w.handle(340, layout);
    }
    w.group(0, "ENDTAB");
    w.group(0, "ENDSEC");

    w.group(0, "SECTION");
    w.group(2, "BLOCKS");
    for (begin, end, record, name, paper) in [
        (blocks[0], blocks[1], ms_record, "*Model_Space", false),
        (blocks[2], blocks[3], ps_record, "*Paper_Space", true),
    ] {
        w.group(0, "BLOCK");
        w.handle(5, begin);
        w.handle(330, record);
        w.group(100, "AcDbEntity");
        if paper {
            w.group(67, 1);
        }
        w.group(8, "0");
        w.group(100, "AcDbBlockBegin");
        w.group(2, name);
        w.group(70, 0);
        w.real(10, 0.0);
        w.real(20, 0.0);
        w.real(30, 0.0);
        w.group(3, name);
        w.group(1, "");
        w.group(0, "ENDBLK");
        w.handle(5, end);
        w.handle(330, record);
        w.group(100, "AcDbEntity");
        if paper {
            w.group(67, 1);
        }
        w.group(8, "0");
        w.group(100, "AcDbBlockEnd");
    }
    let entities = Entities {
        sheet,
        layers: &layers,
        outline_layers: &outline_layers,
        entity_handles: &entity_handles,
        line_handles: &line_handles,
        height,
    };
    for b in &sheet_blocks {
        w.block_begin(b.begin, b.record, &b.name, b.base);
        let on_sheet = |s: Option<usize>| s == Some(b.index);
        entities.write(
            &mut w,
            b.record,
            |k| on_sheet(sheet.sheets.as_ref().map(|s| s[k])),
            |k| on_sheet(line_sheets.as_ref().map(|s| s[k])),
        );
        w.group(0, "ENDBLK");
        w.handle(5, b.end);
        w.handle(330, b.record);
        w.group(100, "AcDbEntity");
        w.group(8, "0");
        w.group(100, "AcDbBlockEnd");
    }
    w.group(0, "ENDSEC");

    w.group(0, "SECTION");
    w.group(2, "ENTITIES");
    if sheet_blocks.is_empty() {
        entities.write(&mut w, ms_record, |_| true, |_| true);
    }
    // Each sheet's block inserted at its base point: the drawing shows the nested layout.
    for b in &sheet_blocks {
        w.group(0, "INSERT");
        w.handle(5, b.insert);
        w.handle(330, ms_record);
        w.group(100, "AcDbEntity");
        w.group(8, "0");
        w.group(100, "AcDbBlockReference");
        w.group(2, &b.name);
        w.real(10, b.base.x);
        w.real(20, b.base.y);
        w.real(30, 0.0);
    }
    w.group(0, "ENDSEC");

    w.group(0, "SECTION");
    w.group(2, "OBJECTS");
    w.group(0, "DICTIONARY");
    w.handle(5, handle::ROOT);
    w.group(330, 0);
    w.group(100, "AcDbDictionary");
    w.group(281, 1);
    w.group(3, "ACAD_GROUP");
    w.handle(350, handle::GROUPS);
    w.group(3, "ACAD_LAYOUT");
    w.handle(350, handle::LAYOUTS);
    w.group(0, "DICTIONARY");
    w.handle(5, handle::GROUPS);
    w.handle(330, handle::ROOT);
    w.group(100, "AcDbDictionary");
    w.group(281, 1);
    w.group(0, "DICTIONARY");
    w.handle(5, handle::LAYOUTS);
    w.handle(330, handle::ROOT);
    w.group(100, "AcDbDictionary");
    w.group(281, 1);
    w.group(3, "Model");
    w.handle(350, ms_layout);
    w.group(3, "Layout1");
    w.handle(350, ps_layout);
    for (h, name, record, order) in [
        (ms_layout, "Model", ms_record, 0),
        (ps_layout, "Layout1", ps_record, 1),
    ] {
        layout(&mut w, h, name, record, order);
    }
    w.group(0, "ENDSEC");
    w.group(0, "EOF");
    Ok(w.out.into_bytes())
}

/// The block of one sheet (`fab.nest`): its name, the sheet index, its base point (the lower-left
/// corner of what is on the sheet, mm) and its handles.
struct SheetBlock {
    name: String,
    index: usize,
    base: DVec2,
    record: u64,
    begin: u64,
    end: u64,
    insert: u64,
}

/// The sheets that hold something, in order, with the lower-left corner of their contents
/// (outlines, fold lines and marks). Empty when the outlines are not nested on sheets.
fn sheet_contents(sheet: &Sheet, line_sheets: Option<&[usize]>) -> Vec<(usize, DVec2)> {
    let Some(sheets) = &sheet.sheets else {
        return Vec::new();
    };
    let mut corners: std::collections::BTreeMap<usize, DVec2> = std::collections::BTreeMap::new();
    let mut extend = |s: usize, points: &[DVec2]| {
        let lo = points
            .iter()
            .fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
        let c = corners.entry(s).or_insert(lo);
        *c = c.min(lo);
    };
    for (k, (pts, _)) in sheet.paths.iter().enumerate() {
        extend(sheets[k], pts);
    }
    if let Some(lines) = line_sheets {
        for ((pts, _), &s) in sheet.folds.iter().chain(&sheet.marks).zip(lines) {
            extend(s, pts);
        }
    }
    corners.into_iter().collect()
}

/// What the entities of a drawing are written from: the sheet, the layers and the handles.
struct Entities<'a> {
    sheet: &'a Sheet,
    layers: &'a [LayerEntry],
    outline_layers: &'a [(usize, usize)],
    entity_handles: &'a [(u64, u64)],
    line_handles: &'a [(u64, u64)],
    height: f64,
}

impl Entities<'_> {
    /// Writes the outlines `keep_outline` keeps with their labels, then the fold lines and marks
    /// (numbered folds first) `keep_line` keeps with their texts, owned by block record `owner`.
    fn write(
        &self,
        w: &mut Writer,
        owner: u64,
        keep_outline: impl Fn(usize) -> bool,
        keep_line: impl Fn(usize) -> bool,
    ) {
        let sheet = self.sheet;
        let height = self.height;
        for (k, ((pts, closed), (label, anchor))) in sheet
            .paths
            .iter()
            .zip(sheet.labels.iter().zip(&sheet.anchors))
            .enumerate()
        {
            if !keep_outline(k) {
                continue;
            }
            let (poly, text) = self.entity_handles[k];
            let (line_layer, text_layer) = self.outline_layers[k];
            w.lwpolyline(poly, owner, &self.layers[line_layer].name, pts, *closed);
            if !label.is_empty() {
                w.text(
                    text,
                    owner,
                    &self.layers[text_layer].name,
                    (label, *anchor, height, 0.0),
                );
            }
        }
        // Fold lines with their angles on FOLDS, marks with their labels on MARKS: the text at the
        // line's middle (a fold) or its inner end (a tick), along the line, half the label height.
        let lines = sheet
            .folds
            .iter()
            .map(|l| (l, 1, true))
            .chain(sheet.marks.iter().map(|l| (l, 2, false)));
        for (k, (((pts, label), layer, middle), &(poly, text))) in
            lines.zip(self.line_handles).enumerate()
        {
            if !keep_line(k) {
                continue;
            }
            let layer = &self.layers[layer].name;
            w.lwpolyline(poly, owner, layer, pts, false);
            if !label.is_empty() {
                let (a, b) = (pts[0], pts[pts.len() - 1]);
                let at = if middle { (a + b) * 0.5 } else { b };
                let mut angle = (b - a).y.atan2((b - a).x).to_degrees();
                if !(-90.0..=90.0).contains(&angle) {
                    angle -= 180.0f64.copysign(angle);
                }
                w.text(text, owner, layer, (label, at, 0.5 * height, angle));
            }
        }
    }
}

impl Writer {
    /// The BLOCK entity that opens a block definition on layer 0 with its base point.
    fn block_begin(&mut self, h: u64, record: u64, name: &str, base: DVec2) {
        self.group(0, "BLOCK");
        self.handle(5, h);
        self.handle(330, record);
        self.group(100, "AcDbEntity");
        self.group(8, "0");
        self.group(100, "AcDbBlockBegin");
        self.group(2, name);
        self.group(70, 0);
        self.real(10, base.x);
        self.real(20, base.y);
        self.real(30, 0.0);
        self.group(3, name);
        self.group(1, "");
    }

    /// An LWPOLYLINE entity.
    fn lwpolyline(&mut self, h: u64, owner: u64, layer: &str, pts: &[DVec2], closed: bool) {
        self.group(0, "LWPOLYLINE");
        self.handle(5, h);
        self.handle(330, owner);
        self.group(100, "AcDbEntity");
        self.group(8, layer);
        self.group(100, "AcDbPolyline");
        self.group(90, pts.len());
        self.group(70, u8::from(closed));
        for p in pts {
            self.real(10, p.x);
            self.real(20, p.y);
        }
    }

    /// A TEXT entity centred on `at`: (text, at, height, rotation in degrees).
    fn text(
        &mut self,
        h: u64,
        owner: u64,
        layer: &str,
        (label, at, height, angle): (&str, DVec2, f64, f64),
    ) {
        self.group(0, "TEXT");
        self.handle(5, h);
        self.handle(330, owner);
        self.group(100, "AcDbEntity");
        self.group(8, layer);
        self.group(100, "AcDbText");
        self.real(10, at.x);
        self.real(20, at.y);
        self.real(30, 0.0);
        self.real(40, height);
        self.group(1, dxf_text(label));
        if angle != 0.0 {
            self.real(50, angle);
        }
        self.group(72, 1);
        self.real(11, at.x);
        self.real(21, at.y);
        self.real(31, 0.0);
        self.group(100, "AcDbText");
        self.group(73, 2);
    }
}

/// A LAYOUT object (plot settings left at their defaults).
fn layout(w: &mut Writer, h: u64, name: &str, record: u64, order: u16) {
    w.group(0, "LAYOUT");
    w.handle(5, h);
    w.handle(330, handle::LAYOUTS);
    w.group(100, "AcDbPlotSettings");
    for code in [1, 4, 6] {
        w.group(code, "");
    }
    for code in 40..=49 {
        w.real(code, 0.0);
    }
    w.real(140, 0.0);
    w.real(141, 0.0);
    w.real(142, 1.0);
    w.real(143, 1.0);
    w.group(70, if order == 0 { 688 } else { 0 });
    w.group(72, 1);
    w.group(73, 0);
    w.group(74, 5);
    w.group(7, "");
    w.group(75, 16);
    w.real(147, 1.0);
    w.real(148, 0.0);
    w.real(149, 0.0);
    w.group(100, "AcDbLayout");
    w.group(1, name);
    w.group(70, 1);
    w.group(71, order);
    for (code, v) in [
        (10, 0.0),
        (20, 0.0),
        (11, 420.0),
        (21, 297.0),
        (12, 0.0),
        (22, 0.0),
        (32, 0.0),
        (14, 0.0),
        (24, 0.0),
        (34, 0.0),
        (15, 0.0),
        (25, 0.0),
        (35, 0.0),
        (146, 0.0),
        (13, 0.0),
        (23, 0.0),
        (33, 0.0),
        (16, 1.0),
        (26, 0.0),
        (36, 0.0),
        (17, 0.0),
        (27, 1.0),
        (37, 0.0),
    ] {
        w.real(code, v);
    }
    w.group(76, 0);
    w.handle(330, record);
}

/// A label as one line of DXF text: line breaks and other control characters become spaces.
fn dxf_text(label: &str) -> String {
    label
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_names_are_clean_and_unique() {
        let mut taken = HashSet::new();
        let a = layer_name("s 1", 0, &taken);
        assert_eq!(a, "STRIP_s_1");
        taken.insert(a.to_ascii_uppercase());
        assert_eq!(layer_name("S_1", 3, &taken), "STRIP_S_1_3");
        assert_eq!(layer_name("", 4, &taken), "STRIP_4");
    }
}
