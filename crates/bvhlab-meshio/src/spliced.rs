//! A reader over a replaced head followed by the rest of a byte slice, without copying the
//! rest: how a file is shown to `stl_io` with its first bytes changed.
//!
//! `stl_io` picks ASCII or binary itself, by whether the first line starts with `solid `; this
//! crate decides that better (see `format`), and then hands `stl_io` a head that leads it the
//! same way: 80 zero bytes in place of a binary file's header, or `solid \n` in place of an
//! ASCII file's first line (which `stl_io` refuses when the name after `solid` is missing).

use std::io::{self, Read, Seek, SeekFrom};

/// `head` followed by `body`, readable and seekable as one stream.
pub(crate) struct Spliced<'a> {
    head: &'a [u8],
    body: &'a [u8],
    position: u64,
}

impl<'a> Spliced<'a> {
    /// The stream `head ++ body`, positioned at its start.
    pub(crate) fn new(head: &'a [u8], body: &'a [u8]) -> Self {
        Self {
            head,
            body,
            position: 0,
        }
    }

    fn len(&self) -> u64 {
        (self.head.len() + self.body.len()) as u64
    }
}

impl Read for Spliced<'_> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let at = usize::try_from(self.position).unwrap_or(usize::MAX);
        let rest = if at < self.head.len() {
            &self.head[at..]
        } else {
            self.body.get(at - self.head.len()..).unwrap_or_default()
        };
        let n = rest.len().min(buf.len());
        buf[..n].copy_from_slice(&rest[..n]);
        self.position += n as u64;
        Ok(n)
    }
}

impl Seek for Spliced<'_> {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        let target = match to {
            SeekFrom::Start(at) => Some(at),
            SeekFrom::End(delta) => self.len().checked_add_signed(delta),
            SeekFrom::Current(delta) => self.position.checked_add_signed(delta),
        };
        let target = target
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "seek before the start"))?;
        self.position = target;
        Ok(target)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_head_then_the_body_and_seeks_back() {
        let mut spliced = Spliced::new(b"abc", b"defgh");
        let mut all = Vec::new();
        spliced.read_to_end(&mut all).expect("in memory");
        assert_eq!(all, b"abcdefgh");
        spliced.seek(SeekFrom::Start(2)).expect("inside");
        let mut two = [0; 2];
        spliced.read_exact(&mut two).expect("inside");
        assert_eq!(&two, b"cd");
        spliced.seek(SeekFrom::End(-1)).expect("inside");
        spliced.read_exact(&mut two[..1]).expect("inside");
        assert_eq!(two[0], b'h');
        assert!(spliced.seek(SeekFrom::Current(-9)).is_err());
        spliced
            .seek(SeekFrom::Start(20))
            .expect("past the end is allowed");
        assert_eq!(spliced.read(&mut two).expect("at the end"), 0);
    }
}
