//! The public contract of issue 2, exercised exactly as code outside the repository uses it.
