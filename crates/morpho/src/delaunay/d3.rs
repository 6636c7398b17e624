//! TODO(helper): issue 3.
