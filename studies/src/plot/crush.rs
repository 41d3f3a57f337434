//! The crush channel's panels: crush (dynamic, then permanent once the
//! contact ended), crush rate, and deceleration with its CFC 60 line.
//!
//! After the end of contact the crush channel keeps changing as the bodies
//! move apart, while the structure's crush stays at the permanent crush:
//! the panel draws the permanent crush from there on, and the channel
//! light and dashed, named for what it then measures.

use super::channels::filtered_lines;
use super::panels::{ms, with_unit};
use super::{Line, Panel, Style};
use lagrangian_sim::scenario::Signal;
use lagrangian_sim::simulate::SimulationResult;

/// The legend of the crush channel after the end of contact.
pub(super) const AFTER_CONTACT: &str = "crush channel after contact (moving apart)";

/// Crush, crush rate and deceleration \[g\] of the crush channel
/// (compression positive).
pub(super) fn crush_panels(result: &SimulationResult, signal: &Signal, g: f64) -> Vec<Panel> {
    let s = &result.samples;
    let t: Vec<f64> = s.iter().map(|x| x.t).collect();
    let motion: Vec<[f64; 3]> = s.iter().map(|x| x.crush_motion(signal)).collect();
    let crush: Vec<f64> = motion.iter().map(|m| m[0]).collect();
    let rate = (s.iter().zip(&motion)).map(|(x, m)| (ms(x.t), m[1]));
    let deceleration: Vec<f64> = motion.iter().map(|m| -m[2] / g).collect();
    let unit = signal.unit.as_deref();
    let contact_end = result.summary.end_of_contact_s;
    let permanent = contact_end.zip(result.summary.permanent_crush_m);
    let rate_unit = unit.map(|u| format!("{u}/s"));
    vec![
        Panel::time(
            "Crush",
            &with_unit("crush", unit),
            crush_lines(&t, &crush, permanent),
        ),
        Panel::time(
            "Crush rate",
            &with_unit("crush rate", rate_unit.as_deref()),
            vec![Line::solid("crush rate", rate.collect(), 0)],
        ),
        Panel::time(
            "Deceleration",
            "deceleration [g]",
            filtered_lines("deceleration", &t, &deceleration, 0, 60.0),
        ),
    ]
}

/// The crush lines over times `t` \[s\]: the channel in full while in
/// contact to the end; with `permanent = (end of contact, permanent
/// crush)`, the channel up to the end of contact, the permanent crush from
/// there to the end, and the channel after it, light and dashed.
pub(super) fn crush_lines(t: &[f64], crush: &[f64], permanent: Option<(f64, f64)>) -> Vec<Line> {
    let points = t.iter().zip(crush).map(|(&t, &c)| (t, c));
    let Some((end, at_end)) = permanent else {
        return vec![Line::solid(
            "crush",
            points.map(|(t, c)| (ms(t), c)).collect(),
            0,
        )];
    };
    let separation = (ms(end), at_end);
    let mut dynamic: Vec<(f64, f64)> = (points.clone())
        .take_while(|&(t, _)| t < end)
        .map(|(t, c)| (ms(t), c))
        .collect();
    dynamic.push(separation);
    let after = std::iter::once(separation)
        .chain(points.filter(|&(t, _)| t > end).map(|(t, c)| (ms(t), c)));
    let last = t.last().map_or(end, |&t| t.max(end));
    vec![
        Line::solid("crush", dynamic, 0),
        Line::solid("permanent crush", vec![separation, (ms(last), at_end)], 1),
        Line::new(AFTER_CONTACT, after.collect(), 0, Style::Dashed),
    ]
}
