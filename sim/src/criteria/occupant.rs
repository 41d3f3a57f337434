//! The occupant criteria of a set of channels: which channels each
//! criterion reads, the filter its standard asks for, and the criterion.

use super::dummy::NECK_OFFSET;
use super::{CLIP_DURATION, Criterion, Dummy, HIC15_WINDOW, HIC36_WINDOW};
use super::{clip, hic, nij, occipital_moment, viscous_criterion};
use crate::pulse::{STANDARD_GRAVITY, cfc::min_sample_rate, cfc_filter};
use crate::warning::Warning;
use serde::ser::{Serialize, SerializeMap, Serializer};

/// Where on the occupant a channel measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Body {
    /// The head's centre of gravity.
    Head,
    /// The thorax (acceleration at the spine, deflection of the sternum).
    Chest,
    /// The upper neck load cell.
    UpperNeck,
    /// The left femur load cell.
    FemurLeft,
    /// The right femur load cell.
    FemurRight,
}

/// What a channel measures, along which axis (ISO 6487 / SAE J211 dummy
/// axes: x forward, z down the spine; tension, flexion positive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Measure {
    /// An acceleration \[m/s²\] along `x`, `y`, `z` or their resultant.
    Acceleration(Axis),
    /// A deflection \[m\] (the chest's).
    Deflection,
    /// A force \[N\].
    Force(Axis),
    /// A moment \[N·m\].
    Moment(Axis),
}

/// An axis of a channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Forward.
    X,
    /// To the left... or right: lateral.
    Y,
    /// Vertical (along the spine).
    Z,
    /// The resultant of the three.
    Resultant,
}

/// One channel of the occupant, evenly sampled, in SI units.
#[derive(Clone, Copy, Debug)]
pub struct Measured<'a> {
    /// Its name in messages (a channel code, a column).
    pub name: &'a str,
    /// Where it measures.
    pub body: Body,
    /// What it measures.
    pub measure: Measure,
    /// The time of the first sample \[s\].
    pub t0: f64,
    /// The sample period \[s\].
    pub dt: f64,
    /// The samples.
    pub values: &'a [f64],
    /// The CFC class already applied (`None`: unfiltered).
    pub filtered: Option<f64>,
}

/// A criterion's value and the channels it was computed from.
#[derive(Clone, Debug, PartialEq)]
pub struct Rated {
    /// Which criterion.
    pub criterion: Criterion,
    /// Its value in [`Criterion::unit`].
    pub value: f64,
    /// The channels it read.
    pub from: Vec<String>,
    /// When it is reached: an interval (HIC) or a time (the others),
    /// where the criterion has one \[s\].
    pub when: Option<(f64, f64)>,
}

/// The criteria a set of channels gives, and why those it would have given
/// are missing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Criteria {
    /// The dummy whose constants were used.
    pub dummy: Option<Dummy>,
    /// The criteria, in [`Criterion::ALL`]'s order.
    pub rated: Vec<Rated>,
    /// A channel that is there but cannot be rated (a filter class its rate
    /// cannot give, no dummy for VC or Nij).
    pub warnings: Vec<Warning>,
}

impl Criteria {
    /// No criteria.
    pub const EMPTY: Criteria = Criteria {
        dummy: None,
        rated: Vec::new(),
        warnings: Vec::new(),
    };

    /// Whether nothing is rated.
    pub fn is_empty(&self) -> bool {
        self.rated.is_empty()
    }

    /// The value of `criterion`, if rated.
    pub fn get(&self, criterion: Criterion) -> Option<f64> {
        self.rated
            .iter()
            .find(|r| r.criterion == criterion)
            .map(|r| r.value)
    }

    /// Adds a criterion computed elsewhere (the vehicle's), keeping
    /// [`Criterion::ALL`]'s order.
    pub fn insert(&mut self, rated: Rated) {
        self.rated.retain(|r| r.criterion != rated.criterion);
        self.rated.push(rated);
        let order = |c: Criterion| Criterion::ALL.iter().position(|x| *x == c);
        self.rated.sort_by_key(|r| order(r.criterion));
    }
}

/// `{"hic15": 512.3, …}`: the rated criteria by key.
impl Serialize for Criteria {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.rated.len()))?;
        for r in &self.rated {
            map.serialize_entry(r.criterion.key(), &r.value)?;
        }
        map.end()
    }
}

/// The occupant criteria of `channels`: every criterion whose channels are
/// there, each from the channels filtered at its class
/// ([`Criterion::filter_class`]); VC and Nij with `dummy`'s constants.
pub fn rate(channels: &[Measured], dummy: Option<Dummy>) -> Criteria {
    let mut out = Criteria {
        dummy,
        ..Criteria::default()
    };
    head(channels, &mut out);
    chest(channels, dummy, &mut out);
    neck(channels, dummy, &mut out);
    femur(channels, &mut out);
    out
}

/// A channel's samples at `cfc`: as they are where already filtered at
/// that class, else filtered now (a channel filtered at a lower class is
/// refused: what it lost cannot be restored).
fn at_class(m: &Measured, cfc: f64, criterion: Criterion, out: &mut Criteria) -> Option<Vec<f64>> {
    match m.filtered {
        Some(done) if done == cfc => return Some(m.values.to_vec()),
        Some(done) if done < cfc => {
            out.warnings.push(Warning::NotRated {
                criterion: criterion.key(),
                reason: format!(
                    "channel `{}` is filtered at CFC {done}, and {} needs CFC {cfc}",
                    m.name,
                    criterion.label()
                ),
            });
            return None;
        }
        _ => {}
    }
    match cfc_filter(m.values, m.dt, cfc) {
        Ok(filtered) => Some(filtered),
        Err(_) => {
            out.warnings.push(Warning::FilterClass {
                cfc,
                period: m.dt,
                min_rate: min_sample_rate(cfc),
                consequence: format!(
                    "{} of channel `{}` is not computed",
                    criterion.label(),
                    m.name
                ),
            });
            None
        }
    }
}

fn find<'a>(
    channels: &'a [Measured<'a>],
    body: Body,
    measure: Measure,
) -> Option<&'a Measured<'a>> {
    channels
        .iter()
        .find(|m| m.body == body && m.measure == measure)
}

/// The resultant acceleration of `body` at `cfc` in g, from its resultant
/// channel or from the components it has (each filtered, then combined),
/// with the channels read.
fn resultant_g(
    channels: &[Measured],
    body: Body,
    criterion: Criterion,
    out: &mut Criteria,
) -> Option<(Vec<f64>, Vec<String>, f64, f64)> {
    let cfc = criterion.filter_class()?;
    if let Some(m) = find(channels, body, Measure::Acceleration(Axis::Resultant)) {
        let a = at_class(m, cfc, criterion, out)?;
        let g = a.iter().map(|x| x.abs() / STANDARD_GRAVITY).collect();
        return Some((g, vec![m.name.to_string()], m.t0, m.dt));
    }
    let parts: Vec<&Measured> = [Axis::X, Axis::Y, Axis::Z]
        .into_iter()
        .filter_map(|axis| find(channels, body, Measure::Acceleration(axis)))
        .collect();
    let first = *parts.first()?;
    if parts
        .iter()
        .any(|p| p.values.len() != first.values.len() || p.dt != first.dt)
    {
        out.warnings.push(Warning::NotRated {
            criterion: criterion.key(),
            reason: format!("the {body:?} acceleration components are not sampled alike"),
        });
        return None;
    }
    let mut sum = vec![0.0; first.values.len()];
    for p in &parts {
        for (s, x) in sum.iter_mut().zip(at_class(p, cfc, criterion, out)?) {
            *s += x * x;
        }
    }
    let g = sum.iter().map(|s| s.sqrt() / STANDARD_GRAVITY).collect();
    let names = parts.iter().map(|p| p.name.to_string()).collect();
    Some((g, names, first.t0, first.dt))
}

fn head(channels: &[Measured], out: &mut Criteria) {
    for (criterion, window) in [
        (Criterion::Hic15, HIC15_WINDOW),
        (Criterion::Hic36, HIC36_WINDOW),
    ] {
        let Some((a, from, t0, dt)) = resultant_g(channels, Body::Head, criterion, out) else {
            continue;
        };
        if let Some(h) = hic(&a, t0, dt, window) {
            out.insert(Rated {
                criterion,
                value: h.value,
                from,
                when: Some((h.t1, h.t2)),
            });
        }
    }
    clip_of(channels, Body::Head, Criterion::Head3ms, out);
}

fn clip_of(channels: &[Measured], body: Body, criterion: Criterion, out: &mut Criteria) {
    let Some((a, from, _, dt)) = resultant_g(channels, body, criterion, out) else {
        return;
    };
    if let Some(value) = clip(&a, dt, CLIP_DURATION) {
        out.insert(Rated {
            criterion,
            value,
            from,
            when: None,
        });
    }
}

fn chest(channels: &[Measured], dummy: Option<Dummy>, out: &mut Criteria) {
    clip_of(channels, Body::Chest, Criterion::Chest3ms, out);
    let Some(m) = find(channels, Body::Chest, Measure::Deflection) else {
        return;
    };
    let Some(d) = at_class(m, 180.0, Criterion::ChestDeflection, out) else {
        return;
    };
    let from = vec![m.name.to_string()];
    let (k, peak) = (d.iter().enumerate()).fold((0, 0.0f64), |best, (k, x)| {
        if x.abs() > best.1 { (k, x.abs()) } else { best }
    });
    let at = m.t0 + k as f64 * m.dt;
    out.insert(Rated {
        criterion: Criterion::ChestDeflection,
        value: peak * 1e3,
        from: from.clone(),
        when: Some((at, at)),
    });
    let Some(dummy) = needs_dummy(dummy, Criterion::Vc, out) else {
        return;
    };
    let (scale, depth) = dummy.viscous_constants();
    if let Some(vc) = viscous_criterion(&d, m.t0, m.dt, scale, depth) {
        out.insert(Rated {
            criterion: Criterion::Vc,
            value: vc.value,
            from,
            when: Some((vc.time, vc.time)),
        });
    }
}

fn needs_dummy(dummy: Option<Dummy>, criterion: Criterion, out: &mut Criteria) -> Option<Dummy> {
    if dummy.is_none() {
        out.warnings.push(Warning::NotRated {
            criterion: criterion.key(),
            reason: format!(
                "{} takes the dummy's constants: name the dummy",
                criterion.label()
            ),
        });
    }
    dummy
}

fn intercepts_of(dummy: Dummy, out: &mut Criteria) -> Option<super::NijIntercepts> {
    let intercepts = dummy.nij_intercepts();
    if intercepts.is_none() {
        out.warnings.push(Warning::NotRated {
            criterion: Criterion::Nij.key(),
            reason: format!("FMVSS 208 gives no Nij intercepts for the {dummy}"),
        });
    }
    intercepts
}

fn neck(channels: &[Measured], dummy: Option<Dummy>, out: &mut Criteria) {
    let fz_channel = find(channels, Body::UpperNeck, Measure::Force(Axis::Z));
    let fx_channel = find(channels, Body::UpperNeck, Measure::Force(Axis::X));
    let fz = fz_channel.and_then(|m| Some((m, at_class(m, 600.0, Criterion::NeckTension, out)?)));
    let fx = fx_channel.and_then(|m| Some((m, at_class(m, 600.0, Criterion::NeckShear, out)?)));
    if let Some((m, f)) = &fz {
        let tension = f.iter().fold(0.0f64, |a, &x| a.max(x));
        let compression = f.iter().fold(0.0f64, |a, &x| a.max(-x));
        for (criterion, value) in [
            (Criterion::NeckTension, tension),
            (Criterion::NeckCompression, compression),
        ] {
            out.insert(Rated {
                criterion,
                value: value / 1e3,
                from: vec![m.name.into()],
                when: None,
            });
        }
    }
    if let Some((m, f)) = &fx {
        let shear = f.iter().fold(0.0f64, |a, &x| a.max(x.abs()));
        out.insert(Rated {
            criterion: Criterion::NeckShear,
            value: shear / 1e3,
            from: vec![m.name.into()],
            when: None,
        });
    }
    let Some(my_m) = find(channels, Body::UpperNeck, Measure::Moment(Axis::Y)) else {
        return;
    };
    let Some(my) = at_class(my_m, 600.0, Criterion::NeckExtension, out) else {
        return;
    };
    // The moment at the occipital condyle, where the shear is there.
    let mut from = vec![my_m.name.to_string()];
    let moment = match &fx {
        Some((fx_m, fx)) if fx.len() == my.len() => {
            from.push(fx_m.name.to_string());
            occipital_moment(&my, fx, NECK_OFFSET)
        }
        _ => my,
    };
    let flexion = moment.iter().fold(0.0f64, |a, &m| a.max(m));
    let extension = moment.iter().fold(0.0f64, |a, &m| a.max(-m));
    for (criterion, value) in [
        (Criterion::NeckFlexion, flexion),
        (Criterion::NeckExtension, extension),
    ] {
        let from = from.clone();
        out.insert(Rated {
            criterion,
            value,
            from,
            when: None,
        });
    }
    let Some((fz_m, fz)) = &fz else {
        return;
    };
    let Some(intercepts) =
        needs_dummy(dummy, Criterion::Nij, out).and_then(|d| intercepts_of(d, out))
    else {
        return;
    };
    from.insert(0, fz_m.name.to_string());
    if let Some(n) = nij(fz, &moment, fz_m.t0, fz_m.dt, &intercepts) {
        let when = Some((n.time, n.time));
        out.insert(Rated {
            criterion: Criterion::Nij,
            value: n.value,
            from,
            when,
        });
    }
}

/// The largest axial compression of either femur (compression negative,
/// as ISO 6487 signs it).
fn femur(channels: &[Measured], out: &mut Criteria) {
    let mut best: Option<(f64, String)> = None;
    for body in [Body::FemurLeft, Body::FemurRight] {
        let Some(m) = find(channels, body, Measure::Force(Axis::Z)) else {
            continue;
        };
        let Some(f) = at_class(m, 600.0, Criterion::FemurMax, out) else {
            continue;
        };
        let compression = f.iter().fold(0.0f64, |a, &x| a.max(-x));
        if best.as_ref().is_none_or(|(b, _)| compression > *b) {
            best = Some((compression, m.name.to_string()));
        }
    }
    if let Some((value, name)) = best {
        out.insert(Rated {
            criterion: Criterion::FemurMax,
            value: value / 1e3,
            from: vec![name],
            when: None,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel<'a>(name: &'a str, body: Body, measure: Measure, values: &'a [f64]) -> Measured<'a> {
        Measured {
            name,
            body,
            measure,
            t0: 0.0,
            dt: 1e-4,
            values,
            filtered: None,
        }
    }

    #[test]
    fn the_head_resultant_combines_the_components_it_has() {
        // 3-4-5: x and z components of a 50 g plateau.
        let x: Vec<f64> = (0..400)
            .map(|k| {
                if (100..300).contains(&k) {
                    30.0 * STANDARD_GRAVITY
                } else {
                    0.0
                }
            })
            .collect();
        let z: Vec<f64> = x.iter().map(|a| a * 4.0 / 3.0).collect();
        let both = [
            channel("head x", Body::Head, Measure::Acceleration(Axis::X), &x),
            channel("head z", Body::Head, Measure::Acceleration(Axis::Z), &z),
        ];
        let criteria = rate(&both, None);
        let clip = criteria.get(Criterion::Head3ms).unwrap();
        assert!((clip - 50.0).abs() < 0.5, "{clip}");
        let hic = criteria
            .rated
            .iter()
            .find(|r| r.criterion == Criterion::Hic15)
            .unwrap();
        assert_eq!(hic.from, ["head x", "head z"]);
        assert!(criteria.get(Criterion::Chest3ms).is_none());
    }

    #[test]
    fn a_channel_filtered_below_the_class_is_not_rated() {
        let a = vec![10.0; 400];
        let mut head = channel(
            "11HEAD0000H3ACXD",
            Body::Head,
            Measure::Acceleration(Axis::X),
            &a,
        );
        head.filtered = Some(60.0);
        let criteria = rate(&[head], None);
        assert!(criteria.rated.is_empty());
        assert_eq!(criteria.warnings[0].kind(), "criterion_not_rated");
        assert!(
            criteria.warnings[0]
                .message()
                .contains("CFC 60, and HIC15 needs CFC 1000")
        );
    }

    #[test]
    fn vc_and_nij_without_a_dummy_are_warnings() {
        let d: Vec<f64> = (0..400)
            .map(|k| -0.03 * (k as f64 / 400.0 * 3.1).sin())
            .collect();
        let f = vec![1000.0; 400];
        let m = vec![20.0; 400];
        let channels = [
            channel("deflection", Body::Chest, Measure::Deflection, &d),
            channel("fz", Body::UpperNeck, Measure::Force(Axis::Z), &f),
            channel("my", Body::UpperNeck, Measure::Moment(Axis::Y), &m),
        ];
        let criteria = rate(&channels, None);
        let kinds: Vec<_> = criteria.warnings.iter().map(|w| w.message()).collect();
        assert!(kinds[0].contains("`vc_mps` is not rated"), "{kinds:?}");
        assert!(kinds[1].contains("`nij` is not rated"), "{kinds:?}");
        assert!(criteria.get(Criterion::ChestDeflection).unwrap() > 29.0);
        let rated = rate(&channels, Some(Dummy::Hybrid3Male50));
        assert!(rated.warnings.is_empty());
        let nij = 1000.0 / 6806.0 + 20.0 / 310.0;
        assert!(
            (rated.get(Criterion::Nij).unwrap() - nij).abs() < 1e-3,
            "{:?}",
            rated.get(Criterion::Nij)
        );
    }
}
