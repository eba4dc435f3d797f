//! Units and their conversion to SI.
