//! The channel code against the examples of the reference notes and RED B.

use super::*;

#[test]
fn a_dummy_head_channel_reads_field_by_field() {
    // RED B: vehicle 1, position 1 (front left), head, fine locations 00 00,
    // Hybrid III 50th male, acceleration, x, CFC 1000.
    let code = ChannelCode::parse("11HEAD0000H3ACXA").unwrap();
    assert_eq!(code.test_object(), TestObject::Vehicle(1));
    assert_eq!(code.position(), '1');
    assert_eq!(code.main_location(), "HEAD");
    assert_eq!(code.main_location_name(), Some(("Head", Category::Dummy)));
    assert_eq!(code.fine_location(1), Some("00"));
    assert_eq!(code.fine_location(2), Some("00"));
    assert_eq!(code.fine_location(3), Some("H3"));
    assert_eq!(code.fine_location(4), None);
    assert_eq!(code.dummy().map(|d| d.code()), Some("H3"));
    assert_eq!(
        code.dummy().unwrap().name(),
        "Hybrid III Mid-Sized Adult Male Dummy"
    );
    assert_eq!(code.dimension(), Dimension::Acceleration);
    assert_eq!(code.dimension().si_unit(), Some("m/(s*s)"));
    assert_eq!(code.direction(), Direction::X);
    assert_eq!(code.filter_class(), FilterClass::A);
    assert_eq!(code.filter_class().cfc(), Some(1000.0));
    assert_eq!(code.to_string(), "11HEAD0000H3ACXA");
}

#[test]
fn the_vehicle_and_barrier_codes_of_the_notes_are_valid() {
    let cg = ChannelCode::parse("10VEHCCG0000ACXD").unwrap();
    assert_eq!(
        cg.main_location_name(),
        Some(("Vehicle", Category::Vehicle))
    );
    assert_eq!(cg.fine_location(1), Some("CG"));
    assert_eq!(cg.filter_class().cfc(), Some(60.0));
    assert_eq!(cg.dummy(), None);
    let seat = ChannelCode::parse("10SEATLERE00ACXP").unwrap();
    assert_eq!(seat.filter_class(), FilterClass::PrefilteredAbove1000);
    assert_eq!(seat.filter_class().cfc(), None);
    let barrier = ChannelCode::parse("B0FBAR000000FOXP").unwrap();
    assert_eq!(barrier.test_object(), TestObject::FixedBarrier);
    assert_eq!(barrier.dimension(), Dimension::Force);
    assert_eq!(barrier.dimension().si_unit(), Some("N"));
    let neck = ChannelCode::parse("11NECKUP00H3MOYB").unwrap();
    assert_eq!(
        (neck.dimension(), neck.direction()),
        (Dimension::Moment, Direction::Y)
    );
    assert_eq!(neck.filter_class().cfc(), Some(600.0));
    let resultant = ChannelCode::parse("11CHST0000H3ACRC").unwrap();
    assert_eq!(resultant.direction(), Direction::Resultant);
    assert_eq!(resultant.filter_class().cfc(), Some(180.0));
}

#[test]
fn each_cfc_class_has_its_frequency() {
    let cfc = |class: char| {
        let code = format!("10VEHCCG0000ACX{class}");
        ChannelCode::parse(&code).unwrap().filter_class().cfc()
    };
    assert_eq!(cfc('A'), Some(1000.0));
    assert_eq!(cfc('B'), Some(600.0));
    assert_eq!(cfc('C'), Some(180.0));
    assert_eq!(cfc('D'), Some(60.0));
    assert_eq!(cfc('0'), None);
    assert_eq!(cfc('X'), None);
}

#[test]
fn a_code_of_the_wrong_length_names_its_length() {
    let e = ChannelCode::parse("10VEHCCG0000AC").unwrap_err();
    assert_eq!(
        e,
        CodeError::Length {
            code: "10VEHCCG0000AC".into(),
            length: 14
        }
    );
    assert!(e.to_string().contains("14 characters"), "{e}");
}

#[test]
fn a_bad_field_names_its_position_the_field_and_what_it_found() {
    let field = |text: &str| match ChannelCode::parse(text).unwrap_err() {
        CodeError::Field {
            position,
            field,
            found,
            ..
        } => (position, field, found),
        e => panic!("{e}"),
    };
    assert_eq!(
        field("Z0VEHCCG0000ACXP"),
        (1, CodeField::TestObject, "Z".into())
    );
    assert_eq!(
        field("10VEHCCG0000QQXP"),
        (13, CodeField::Dimension, "QQ".into())
    );
    assert_eq!(
        field("10VEHCCG0000ACWP"),
        (15, CodeField::Direction, "W".into())
    );
    assert_eq!(
        field("10VEHCCG0000ACXZ"),
        (16, CodeField::FilterClass, "Z".into())
    );
    // A lower-case letter or a wildcard is no code character.
    assert_eq!(
        field("10VEHCcg0000ACXP"),
        (7, CodeField::FineLocation1, "cg".into())
    );
    assert_eq!(
        field("10VE?CCG0000ACXP"),
        (5, CodeField::MainLocation, "VE?C".into())
    );
    let message = ChannelCode::parse("10VEHCCG0000QQXP")
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("physical dimension (position 13) is \"QQ\""),
        "{message}"
    );
}

#[test]
fn lab_specific_dimensions_and_locations_are_codes_without_a_standard_name() {
    let code = ChannelCode::parse("1012AB0000001AX0").unwrap();
    assert_eq!(code.dimension(), Dimension::LaboratorySpecific('A'));
    assert_eq!(code.dimension().code(), "1A");
    assert_eq!(code.dimension().si_unit(), None);
    assert_eq!(code.main_location_name(), None);
}
