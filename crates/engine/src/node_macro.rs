//! The `node!` macro: a node type declared as one documented function.

/// Declares a node type as a plain function whose doc comments become the node's documentation.
///
/// ```
/// use cnets_engine::{node, kinds as k};
///
/// node! {
///     /// Adds two numbers.
///     #[node(id = "demo.add", category = "Math")]
///     pub fn add(
///         /// First term.
///         a: k::Number = 0.0,
///         /// Second term.
///         #[ui(widget = Slider, range = 0.0..=10.0, step = 0.5)]
///         b: k::Number = 0.0,
///     ) -> (
///         /// The sum.
///         sum: k::Number,
///     ) {
///         Ok((a + b,))
///     }
/// }
///
/// let def = add();
/// assert_eq!(def.id, "demo.add");
/// assert_eq!(def.doc, "Adds two numbers.");
/// assert_eq!(def.inputs[1].doc, "Second term.");
/// assert_eq!(def.inputs[1].widget(), cnets_engine::Widget::Slider);
/// assert_eq!(def.inputs[1].hint.soft_range, Some((0.0, 10.0)));
/// ```
///
/// The generated function (`add()` above) returns the [`NodeDef`](crate::NodeDef). Inputs are bound
/// by name in the body, already converted to their Rust types; the body returns `Ok((out1, out2, …))`
/// in output order. Write `fn name[ctx](…)` to receive the [`NodeContext`](crate::NodeContext) as
/// `ctx`; add `flags(Export)` (or `Parameter`, `Import`) inside `#[node(…)]` for special nodes and
/// `name = "Number slider"` for the name designers see. A port may carry `#[ui(…)]` after its doc
/// comment: `widget = Slider` (a [`Widget`](crate::Widget)), `name = "…"`, `range = 0.0..=1.0`,
/// `hard = 0.0..=1.0`, `step = 0.1`, and on outputs `layer = Supports` (a
/// [`Layer`](crate::Layer)) — read by editors instead of guessing from names. A port of kind
/// `k::Choice<E>` is a text with fixed words (a drop-down; checked when a value is set).
#[macro_export]
macro_rules! node {
    (
        $(#[doc = $doc:literal])*
        #[node(id = $id:literal, category = $cat:literal $(, name = $dname:literal)? $(, flags($($flag:ident),* $(,)?))? $(,)?)]
        $vis:vis fn $name:ident $([$ctx:ident])? (
            $( $(#[doc = $idoc:literal])* $(#[ui($($ikey:ident = $ival:expr),* $(,)?)])? $iname:ident : $ikind:ty $(= $idef:expr)? ),* $(,)?
        ) -> (
            $( $(#[doc = $odoc:literal])* $(#[ui($($okey:ident = $oval:expr),* $(,)?)])? $oname:ident : $okind:ty ),* $(,)?
        ) $body:block
    ) => {
        $(#[doc = $doc])*
        $vis fn $name() -> $crate::NodeDef {
            $crate::NodeDef::new($id, $cat, $crate::node::doc_text(&[$($doc),*]))
            $( .with_display_name($dname) )?
            $(
                .input({
                    let port = $crate::PortDef::of::<$ikind>(
                        $crate::node::port_name(stringify!($iname)),
                        $crate::node::doc_text(&[$($idoc),*]),
                    );
                    $( let port = port.with_default($crate::kinds::default_value::<$ikind, _>($idef)); )?
                    $( let port = port.with_hint({
                        #[allow(unused_imports)]
                        use $crate::node::{Layer::*, Role::*, Widget::*};
                        let mut hint = $crate::node::HintBuilder::default();
                        $( hint.$ikey($ival); )*
                        hint.0
                    }); )?
                    port
                })
            )*
            $(
                .output({
                    let port = $crate::PortDef::of::<$okind>(
                        $crate::node::port_name(stringify!($oname)),
                        $crate::node::doc_text(&[$($odoc),*]),
                    );
                    $( let port = port.with_hint({
                        #[allow(unused_imports)]
                        use $crate::node::{Layer::*, Role::*, Widget::*};
                        let mut hint = $crate::node::HintBuilder::default();
                        $( hint.$okey($oval); )*
                        hint.0
                    }); )?
                    port
                })
            )*
            $( $( .flag($crate::NodeFlag::$flag) )* )?
            .run(move |__ctx: &$crate::NodeContext, __inputs: &[$crate::Value]| {
                let mut __it = __inputs.iter();
                $(
                    let $iname = <$ikind as $crate::PortKind>::extract(
                        __it.next().ok_or_else(|| $crate::NodeError::new("missing input"))?,
                        $crate::node::port_name(stringify!($iname)),
                    )?;
                )*
                $( let $ctx: &$crate::NodeContext = __ctx; )?
                let _ = __ctx;
                let ($($oname,)*) =
                    (|| -> ::core::result::Result<_, $crate::NodeError> { $body })()?;
                Ok(vec![$($crate::IntoPort::<$okind>::into_port($oname)),*])
            })
        }
    };
}
