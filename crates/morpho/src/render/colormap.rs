//! Colour maps for scalar values. TODO(helper).
