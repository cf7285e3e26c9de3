#include "thalassa/ocean/gl/effective_fresnel_texture.hpp"

#include "thalassa/ocean/effective_fresnel.hpp"

namespace thalassa::ocean {

EffectiveFresnelTexture::EffectiveFresnelTexture() : texture_(gl::make_texture(GL_TEXTURE_2D)) {
  const EffectiveFresnelTable& table = effective_fresnel_table();
  glTextureStorage2D(texture_.get(), 1, GL_RGBA32F, table.cos_size, table.sigma_size);
  glTextureSubImage2D(texture_.get(), 0, 0, 0, table.cos_size, table.sigma_size, GL_RGBA, GL_FLOAT,
                      table.values.data());
  // Bilinear between the samples (EffectiveFresnelTable::lookup is its CPU twin); the shader
  // clamps its coordinates to the samples' centres, so the edges never blend with a border.
  glTextureParameteri(texture_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture_.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void EffectiveFresnelTexture::add_defines(gl::Defines& defines) {
  defines["EFFECTIVE_FRESNEL_TABLE"] = "1";
}

void EffectiveFresnelTexture::bind() const {
  glBindTextureUnit(kEffectiveFresnelUnit, texture_.get());
}

}  // namespace thalassa::ocean
