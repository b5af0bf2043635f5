//! The cnets desktop editor: a node canvas and a live 3D viewport over the cnets engine.
//!
//! One concept a module, UI logic testable without a window:
//!
//! - [`document`]: the graph document (engine graph + metadata + path), the source of truth;
//!   [`history`]: undo / redo by snapshots, one step per gesture.
//! - [`worker`]: evaluation on a background thread, latest change wins ([`remote`]: or in the web
//!   page's Web Worker); [`preview`] (the
//!   `cnets-preview` crate, shared with `cnets render`): the render scene and figures built from the
//!   results.
//! - [`canvas`]: the node canvas (an egui-snarl view of the graph, kept in sync both ways);
//!   [`palette`]: the searchable node palette; [`widgets`]: inline value editors;
//!   [`mapper`]: the graph-mapper widget; [`list_editor`]: literal lists as tables (a summary on
//!   the node, a window to edit them).
//! - [`viewport`]: the 3D view (a wgpu paint callback through `cnets-render`) and its camera;
//!   [`view_errors`]: failed nodes that are off the canvas, listed in the 3D view.
//! - [`welcome`]: the first visit's hint (the web page).
//! - [`narrow`]: the stacked layout of phones and narrow windows; [`overview`]: the canvas's
//!   minimap when the graph does not fit.
//! - [`menus`], [`file_dialog`]: the menu bar and a built-in path dialog; [`export`]: exports
//!   through the export nodes.
//! - [`library`]: the user library of graphs used as cluster nodes, and reloading cluster files
//!   changed on disk; [`optimization`]: the optimization panel and its runs.
//! - [`recovery`]: autosave and restore after a crash; [`settings`]: recent files, library folder;
//!   [`unsaved`]: the Save / Don't save / Cancel guard on everything that replaces the document;
//!   [`load_failure`]: a file that failed to load, with its diagnostics; [`parameters`]: the
//!   docked parameter panel; [`cluster_ports`]: ports renamed inside an opened cluster keep
//!   their wires; [`page`]: what the web page does for the editor in a browser; [`probe`]:
//!   where named controls were drawn, for scripted window tests.
//! - [`app`]: the editor state and one frame of UI, shared by the window (`main.rs`) and tests.

pub mod app;
pub mod canvas;
pub mod clipboard;
pub mod cluster_ports;
pub mod document;
pub mod document_error;
pub mod drag_solver;
pub mod edit;
pub mod edit_error;
pub mod export;
pub mod export_preview;
pub mod file_dialog;
pub mod history;
pub mod import_watch;
pub mod instance;
pub mod layout;
pub mod library;
pub mod list_editor;
pub mod load_failure;
pub mod mapper;
pub mod menus;
pub mod narrow;
pub mod net_drag;
pub mod opening_notice;
pub mod optimization;
pub mod overview;
pub mod page;
pub mod palette;
pub mod parameters;
pub mod plot;
pub mod probe;
pub mod recovery;
pub mod remote;
pub mod request;
pub mod settings;
pub mod unsaved;
pub mod view_errors;
pub mod viewport;
pub mod welcome;
pub mod widgets;
pub mod worker;

pub use app::{EditorApp, GpuTarget};
pub use cnets_preview as preview;
