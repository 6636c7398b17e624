//! Contour surfaces f = α of rectilinear volumes (Hamann 1991 §3.2–3.3). TODO(helper): issue 6.
