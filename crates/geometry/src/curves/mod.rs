//! Curve operations on polylines: sampling, splines, resampling, transforms.
