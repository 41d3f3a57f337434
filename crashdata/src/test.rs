//! An ISO-MME test as it is held: the test's header, the channel list's
//! header and the channels, each channel on its implicit time base
//! `t = t0 + i·dt`.

use crate::code::ChannelCode;
use crate::text::Header;

/// An ISO-MME test: `<name>.mme` and its `Channel/` folder.
#[derive(Clone, Debug, PartialEq)]
pub struct Test {
    /// The test's name: the stem of its `.mme` and channel files.
    pub name: String,
    /// The `.mme` file's lines, in order.
    pub info: Header,
    /// The `.chn` file's lines, in order (`Instrumentation standard`,
    /// `Number of channels`, `Name of channel 001`, …). Writing replaces
    /// its `Number of channels` and `Name of channel NNN` by those of
    /// [`Test::channels`].
    pub channel_info: Header,
    /// The channels, in the order of their files (`.001`, `.002`, …).
    pub channels: Vec<Channel>,
}

impl Test {
    /// The first channel with code `code`.
    pub fn channel(&self, code: &ChannelCode) -> Option<&Channel> {
        self.channels.iter().find(|c| c.code == *code)
    }
}

/// One channel: its file's header and samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Channel {
    /// `Channel code`.
    pub code: ChannelCode,
    /// Every line of the channel file's header, in order (the fields below
    /// included, as read).
    pub header: Header,
    /// `Unit` (`g`, `N`, `m/s`); empty where the file gives none.
    pub unit: String,
    /// `Time of first sample` \[s\].
    pub t0: f64,
    /// `Sampling interval` \[s\].
    pub dt: f64,
    /// The samples, in `unit`; NaN for a `NOVALUE` sample.
    pub values: Vec<f64>,
}

impl Channel {
    /// The time of each sample, `t0 + i·dt` \[s\].
    pub fn times(&self) -> Vec<f64> {
        (0..self.values.len()).map(|i| self.time(i)).collect()
    }

    /// The time of sample `i`, `t0 + i·dt` \[s\].
    pub fn time(&self, i: usize) -> f64 {
        self.t0 + i as f64 * self.dt
    }

    /// `Name of the channel`, where the header gives one.
    pub fn name(&self) -> Option<&str> {
        self.header.get("Name of the channel")
    }
}
