#include "thalassa/ocean/gl/effective_fresnel_texture.hpp"

#include "thalassa/ocean/effective_fresnel.hpp"

namespace thalassa::ocean {

std::unique_ptr<EffectiveFresnelTexture> EffectiveFresnelTexture::make_if_used(
    const OceanSettings& settings, bool reads_fresnel, bool reflects_sky) {
  const bool table = reads_fresnel && settings.effective_fresnel == "table";
  const bool sky_lobe = reflects_sky && settings.sky_lobe_centre == "fresnel_weighted";
  if (!table && !sky_lobe) return nullptr;
  return std::unique_ptr<EffectiveFresnelTexture>(new EffectiveFresnelTexture(table, sky_lobe));
}

EffectiveFresnelTexture::EffectiveFresnelTexture(bool table, bool sky_lobe)
    : table_(table), sky_lobe_(sky_lobe), texture_(gl::make_texture(GL_TEXTURE_2D)) {
  const EffectiveFresnelTable& values = effective_fresnel_table();
  glTextureStorage2D(texture_.get(), 1, GL_RGBA32F, values.cos_size, values.sigma_size);
  glTextureSubImage2D(texture_.get(), 0, 0, 0, values.cos_size, values.sigma_size, GL_RGBA,
                      GL_FLOAT, values.values.data());
  // Bilinear between the samples (EffectiveFresnelTable::lookup is its CPU twin); the shader
  // clamps its coordinates to the samples' centres, so the edges never blend with a border.
  gl::set_sampling(texture_.get(), {});
}

void EffectiveFresnelTexture::add_defines(gl::Defines& defines) const {
  if (table_) defines["EFFECTIVE_FRESNEL_TABLE"] = "1";
  if (sky_lobe_) defines["SKY_LOBE_FRESNEL_WEIGHTED"] = "1";
}

std::vector<std::string> EffectiveFresnelTexture::built() const {
  std::vector<std::string> list;
  if (table_) list.push_back("ocean.effective_fresnel.table");
  if (sky_lobe_) list.push_back("ocean.sky_lobe_centre.fresnel_weighted");
  return list;
}

void EffectiveFresnelTexture::bind() const {
  glBindTextureUnit(kEffectiveFresnelUnit, texture_.get());
}

}  // namespace thalassa::ocean
