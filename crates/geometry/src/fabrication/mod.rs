//! Supplementary and fabrication tools (paper Sec. 4.4.2): apex from widths, torsion-free axes,
//! support layers, parallel transforms, strips and unrolling, mesh cutting, mirroring and joining.
