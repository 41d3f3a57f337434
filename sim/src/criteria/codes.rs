//! Where a channel of an ISO-MME code measures on a dummy, for the
//! criteria: its main location (`HEAD`, `CHST`, `NECK` with `UP`, `FEMR`
//! with `LE`/`RI`), its physical dimension and direction, the class it is
//! already filtered at and the dummy fine location 3 names.

use super::Dummy;
use super::occupant::{Axis, Body, Measure};
use lagrangian_crashdata::ChannelCode;
use lagrangian_crashdata::code::{Dimension, Direction, FilterClass};

/// The body and measure of `code`'s channel, where a criterion reads it;
/// `None` for every other channel (and for directions with signs other
/// than SAE J211's, which the criteria's signs assume).
pub fn placement(code: &ChannelCode) -> Option<(Body, Measure)> {
    let axis = match code.direction() {
        Direction::X => Axis::X,
        Direction::Y => Axis::Y,
        Direction::Z => Axis::Z,
        Direction::Resultant => Axis::Resultant,
        _ => return None,
    };
    let fine = code.fine_location(1).unwrap_or("00");
    let body = match (code.main_location(), fine) {
        ("HEAD", _) => Body::Head,
        ("CHST", _) => Body::Chest,
        ("NECK", "UP") => Body::UpperNeck,
        ("FEMR", "LE") => Body::FemurLeft,
        ("FEMR", "RI") => Body::FemurRight,
        _ => return None,
    };
    let measure = match code.dimension() {
        Dimension::Acceleration => Measure::Acceleration(axis),
        Dimension::Displacement | Dimension::Distance if body == Body::Chest => Measure::Deflection,
        Dimension::Force => Measure::Force(axis),
        Dimension::Moment => Measure::Moment(axis),
        _ => return None,
    };
    Some((body, measure))
}

/// The CFC class `code`'s channel is already filtered at; `None` for an
/// unfiltered or prefiltered one (which the criteria filter).
pub fn filtered_at(code: &ChannelCode) -> Option<f64> {
    match code.filter_class() {
        FilterClass::Unfiltered
        | FilterClass::PrefilteredAbove1000
        | FilterClass::PrefilteredBelow60 => None,
        class => class.cfc(),
    }
}

/// The dummy of `code`'s fine location 3, where the criteria know it.
pub fn dummy_of(code: &ChannelCode) -> Option<Dummy> {
    code.dummy().and_then(|d| Dummy::parse(d.code()))
}

/// The occupant `code`'s channel belongs to: its test object and seat
/// position (`('1', '1')`, the driver of vehicle 1).
pub fn occupant_of(code: &ChannelCode) -> (char, char) {
    (code.as_str().as_bytes()[0] as char, code.position())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn code(text: &str) -> ChannelCode {
        ChannelCode::parse(text).unwrap()
    }

    #[test]
    fn dummy_channels_are_placed_by_location_dimension_and_direction() {
        let head = code("11HEAD0000H3ACXA");
        assert_eq!(
            placement(&head),
            Some((Body::Head, Measure::Acceleration(Axis::X)))
        );
        assert_eq!(
            (filtered_at(&head), dummy_of(&head)),
            (Some(1000.0), Some(Dummy::Hybrid3Male50))
        );
        assert_eq!(
            placement(&code("11NECKUP00H3FOZA")),
            Some((Body::UpperNeck, Measure::Force(Axis::Z)))
        );
        assert_eq!(
            placement(&code("11NECKUP00H3MOYB")),
            Some((Body::UpperNeck, Measure::Moment(Axis::Y)))
        );
        assert_eq!(
            placement(&code("11CHST0000HFDSXC")),
            Some((Body::Chest, Measure::Deflection))
        );
        assert_eq!(
            placement(&code("13FEMRLE00H3FOZB")),
            Some((Body::FemurLeft, Measure::Force(Axis::Z)))
        );
        assert_eq!(occupant_of(&code("13FEMRLE00H3FOZB")), ('1', '3'));
        assert_eq!(filtered_at(&code("11CHST0000H3ACX0")), None);
    }

    #[test]
    fn other_channels_are_not_placed() {
        assert_eq!(placement(&code("10VEHCCG0000ACXP")), None);
        assert_eq!(placement(&code("11NECKLO00H3FOZA")), None);
        assert_eq!(placement(&code("11HEAD0000H3AC1A")), None);
    }
}
