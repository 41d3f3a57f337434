lagrangian::lagrangian!(file = "specs/no_such_model.lpm");

fn main() {}
